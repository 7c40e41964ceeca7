#include "cnclab/studies/contour_error/feedrate_optimisation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {

// Arc length at each cap knot from the first (mm), by Gauss-Legendre per gap.
std::vector<double> optimisation_knot_arc_lengths(const PlanarPath& path,
                                                  const std::vector<double>& knots) {
  std::vector<double> s(knots.size(), 0.0);
  for (std::size_t k = 0; k + 1 < knots.size(); ++k) {
    s[k + 1] = s[k] + arc_length(path, knots[k], knots[k + 1], 1);
  }
  return s;
}

// Arc length at parameter u, linear between knots (they are ~1 mm apart).
double optimisation_arc_length_at(const std::vector<double>& knots, const std::vector<double>& s,
                                  double u) {
  if (u <= knots.front()) return s.front();
  if (u >= knots.back()) return s.back();
  const auto k =
      static_cast<std::size_t>(std::upper_bound(knots.begin(), knots.end(), u) - knots.begin());
  const double w = (u - knots[k - 1]) / (knots[k] - knots[k - 1]);
  return s[k - 1] + w * (s[k] - s[k - 1]);
}

// Step 3 of the loop (feedrate_optimisation.hpp): lowers the cap knots around
// every tick whose prediction exceeds the target. Returns the ticks over.
std::size_t optimisation_lower_caps(const FeedrateOptimisationOptions& o,
                                    const ReferenceTrajectory& r,
                                    const std::vector<double>& predicted,
                                    const std::vector<double>& s_knots, PathSpeedCap& cap) {
  const double bound = o.tolerance - o.prediction_margin;
  const double target = o.safety_factor * bound;
  std::size_t over = 0;
  for (Eigen::Index k = 0; k < r.samples(); ++k) {
    const double eps = predicted[static_cast<std::size_t>(k)];
    if (!(eps > target)) continue;
    if (eps > bound) ++over;
    const double speed = r.velocity.row(k).norm();
    const double wanted = speed * std::pow(target / eps, 1.0 / o.error_exponent);
    const double s = optimisation_arc_length_at(cap.u, s_knots, r.u[static_cast<std::size_t>(k)]);
    const auto first = std::lower_bound(s_knots.begin(), s_knots.end(), s - o.margin);
    const auto last = std::upper_bound(s_knots.begin(), s_knots.end(), s + o.margin);
    for (auto it = first; it != last; ++it) {
      double& c = cap.speed[static_cast<std::size_t>(it - s_knots.begin())];
      c = std::min(c, wanted);
    }
  }
  return over;
}

}  // namespace

void FeedrateOptimisationOptions::validate() const {
  if (!(tolerance > 0.0 && std::isfinite(tolerance))) {
    throw OptionError("tolerance", shortest_double(tolerance), "must be > 0 and finite [mm]");
  }
  if (!(safety_factor > 0.0 && safety_factor <= 1.0)) {
    throw OptionError("safety_factor", shortest_double(safety_factor), "must be in (0, 1]");
  }
  if (!(prediction_margin >= 0.0 && prediction_margin < tolerance)) {
    throw OptionError("prediction_margin", shortest_double(prediction_margin),
                      "must be in [0, tolerance " + shortest_double(tolerance) + ") [mm]");
  }
  if (!(error_exponent > 0.0 && std::isfinite(error_exponent))) {
    throw OptionError("error_exponent", shortest_double(error_exponent), "must be > 0");
  }
  if (!(margin >= 0.0 && std::isfinite(margin))) {
    throw OptionError("margin", shortest_double(margin), "must be >= 0 and finite [mm]");
  }
  if (max_iterations < 1) {
    throw OptionError("max_iterations", std::to_string(max_iterations), "must be >= 1");
  }
  if (!(min_speed > 0.0 && std::isfinite(min_speed))) {
    throw OptionError("min_speed", shortest_double(min_speed), "must be > 0 [mm/s]");
  }
  try {
    planner.validate();
  } catch (const OptionError& e) {
    throw OptionError("planner." + e.field(), e.value(), e.rule());
  }
}

const char* to_string(OptimisationStatus status) noexcept {
  switch (status) {
    case OptimisationStatus::converged:
      return "converged";
    case OptimisationStatus::max_iterations:
      return "max_iterations";
    case OptimisationStatus::infeasible:
      return "infeasible";
  }
  return "unknown";
}

std::vector<double> predict_contour_error(ContourPredictor& predictor, const PlanarPath& path,
                                          const ReferenceTrajectory& reference) {
  predictor.reset();
  std::vector<double> out(static_cast<std::size_t>(reference.samples()));
  ContourPrediction p;
  for (Eigen::Index k = 0; k < reference.samples(); ++k) {
    const PathPoint point = path.evaluate(reference.u[static_cast<std::size_t>(k)]);
    const PredictorStatus status = predictor.step(reference.velocity.row(k).transpose(), point, p);
    if (status != PredictorStatus::ok) {
      std::ostringstream m;
      m << "contour prediction failed at tick " << k << " (t = " << reference.time[k]
        << " s): " << to_string(status);
      throw Error(m.str());
    }
    out[static_cast<std::size_t>(k)] = std::abs(p.contour_error);
  }
  return out;
}

FeedrateOptimisationResult optimise_feedrate(const PlanarPath& path, ContourPredictor& predictor,
                                             const FeedrateOptimisationOptions& options,
                                             const ProgressCallback& progress) {
  options.validate();
  FeedratePlannerOptions planner = options.planner;
  planner.speed_cap = {};
  FeedrateOptimisationResult res;
  std::vector<double> s_knots;
  for (int it = 0; it < options.max_iterations; ++it) {
    const auto t0 = std::chrono::steady_clock::now();
    res.profile = plan_feedrate(path, planner);
    res.reference = interpolate(path, res.profile, 1e-3);
    res.predicted = predict_contour_error(predictor, path, res.reference);
    if (it == 0) {
      // Cap knots: the unconstrained grid, at the fastest speed the axis
      // velocity limits allow anywhere (no effect until lowered).
      const auto& L = options.planner.limits.axes;
      res.cap = PathSpeedCap::uniform(res.profile.u, std::hypot(L[0].velocity, L[1].velocity));
      s_knots = optimisation_knot_arc_lengths(path, res.cap.u);
    }
    OptimisationIteration rec;
    rec.worst_predicted = *std::max_element(res.predicted.begin(), res.predicted.end());
    rec.time = res.profile.total_time();
    rec.min_cap = *std::min_element(res.cap.speed.begin(), res.cap.speed.end());
    if (it == 0) rec.min_cap = res.cap.speed.front();
    res.history.push_back(rec);
    if (rec.worst_predicted <= options.tolerance - options.prediction_margin) {
      res.status = OptimisationStatus::converged;
      res.reason = "worst predicted contour error " + fixed_decimals(rec.worst_predicted * 1e3, 2) +
                   " um <= tolerance - margin after " + std::to_string(it + 1) + " plan(s)";
      res.history.back().seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      return res;
    }
    res.history.back().ticks_over =
        optimisation_lower_caps(options, res.reference, res.predicted, s_knots, res.cap);
    res.history.back().seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (progress)
      progress("feedrate optimisation (plans)", res.history.size(),
               static_cast<std::size_t>(options.max_iterations));
    const double lowest = *std::min_element(res.cap.speed.begin(), res.cap.speed.end());
    if (lowest < options.min_speed) {
      res.status = OptimisationStatus::infeasible;
      res.reason = "the cap would fall to " + shortest_double(lowest) + " mm/s < min_speed " +
                   shortest_double(options.min_speed) +
                   " mm/s: slowing down does not bring the predicted error (worst " +
                   fixed_decimals(rec.worst_predicted * 1e3, 2) + " um) under the tolerance";
      return res;
    }
    planner.speed_cap = res.cap;
  }
  res.cap = planner.speed_cap;  // the cap of the last plan, not the one lowered after it
  res.status = OptimisationStatus::max_iterations;
  res.reason =
      "worst predicted contour error " + shortest_double(res.history.back().worst_predicted * 1e3) +
      " um still above the tolerance after " + std::to_string(options.max_iterations) + " plans";
  return res;
}

}  // namespace cnclab
