#include "cnclab/studies/contour_error/feedrate_optimisation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/motion/axis_direction.hpp"

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
// every tick whose prediction exceeds the target; with raise_caps, first
// resets every knot to `top` and takes every tick's wanted speed, so knots
// whose window predicts below the target rise. Returns the ticks over.
std::size_t optimisation_lower_caps(const FeedrateOptimisationOptions& o,
                                    const ReferenceTrajectory& r,
                                    const std::vector<double>& predicted,
                                    const std::vector<double>& s_knots, double top,
                                    PathSpeedCap& cap) {
  const std::vector<double> margins = o.tick_margins(r);
  const PathSpeedCap before = cap;
  if (o.raise_caps) std::fill(cap.speed.begin(), cap.speed.end(), top);
  std::size_t over = 0;
  for (Eigen::Index k = 0; k < r.samples(); ++k) {
    const double eps = predicted[static_cast<std::size_t>(k)];
    const double v = r.velocity.row(k).norm();
    if (o.at_standstill(v)) continue;
    const double bound = o.tolerance - margins[static_cast<std::size_t>(k)];
    const double target = std::max(0.0, o.safety_factor * bound);
    if (eps > bound) ++over;
    const bool below = !(eps > target);
    if (below && !(o.raise_caps && eps > 0.0)) continue;
    // Below the target the tick may rise from its cap (whether or not the
    // cap bound it: near standstill the speed says nothing of the cap), above
    // it falls from its speed.
    const double speed = below ? std::max(v, before.at(r.u[static_cast<std::size_t>(k)])) : v;
    const double wanted = std::min(top, speed * std::pow(target / eps, 1.0 / o.error_exponent));
    const double s = optimisation_arc_length_at(cap.u, s_knots, r.u[static_cast<std::size_t>(k)]);
    const auto first = std::lower_bound(s_knots.begin(), s_knots.end(), s - o.margin);
    const auto last = std::upper_bound(s_knots.begin(), s_knots.end(), s + o.margin);
    for (auto it = first; it != last; ++it) {
      double& c = cap.speed[static_cast<std::size_t>(it - s_knots.begin())];
      c = std::min(c, wanted);
    }
  }
  // A knot rises half way (geometrically) towards its wanted speed: the
  // error at a tick follows the feed of the last servo time constants, so a
  // full rise overshoots and the plans oscillate (measured on the S-bend of
  // the test: worst predicted 13 -> 22 -> 12.5 -> 21.6 um).
  if (o.raise_caps) {
    for (std::size_t j = 0; j < cap.speed.size(); ++j) {
      if (cap.speed[j] > before.speed[j]) cap.speed[j] = std::sqrt(cap.speed[j] * before.speed[j]);
    }
  }
  return over;
}

}  // namespace

std::size_t FeedBandMargins::band(double speed) const noexcept {
  return static_cast<std::size_t>(std::upper_bound(edges.begin(), edges.end(), speed) -
                                  edges.begin());
}

double FeedBandMargins::at(double speed, double since_change) const noexcept {
  const std::size_t b = band(speed);
  return after_reversal_at(since_change) ? after_reversal[b] : margin[b];
}

void FeedBandMargins::validate() const {
  if (margin.size() != edges.size() + 1) {
    throw OptionError("margin", std::to_string(margin.size()) + " values",
                      "must be one per band: " + std::to_string(edges.size() + 1));
  }
  for (std::size_t i = 0; i < edges.size(); ++i) {
    if (!(edges[i] > 0.0 && std::isfinite(edges[i])) || (i > 0 && !(edges[i] > edges[i - 1]))) {
      throw OptionError("edges", shortest_double(edges[i]),
                        "must be finite, > 0 and ascending [mm/s]");
    }
  }
  for (const double m : margin) {
    if (!(m >= 0.0 && std::isfinite(m))) {
      throw OptionError("margin", shortest_double(m), "must be >= 0 and finite [mm]");
    }
  }
  if (!(reversal_window >= 0.0 && std::isfinite(reversal_window))) {
    throw OptionError("reversal_window", shortest_double(reversal_window),
                      "must be >= 0 and finite [s]");
  }
  if (after_reversal.size() != (reversal_window > 0.0 ? margin.size() : 0)) {
    throw OptionError("after_reversal", std::to_string(after_reversal.size()) + " values",
                      reversal_window > 0.0
                          ? "must be one per band: " + std::to_string(margin.size())
                          : std::string("must be empty without a reversal_window"));
  }
  for (const double m : after_reversal) {
    if (!(m >= 0.0 && std::isfinite(m))) {
      throw OptionError("after_reversal", shortest_double(m), "must be >= 0 and finite [mm]");
    }
  }
}

std::vector<double> FeedrateOptimisationOptions::tick_margins(const ReferenceTrajectory& r) const {
  std::vector<double> out(static_cast<std::size_t>(r.samples()), prediction_margin);
  if (margin_bands.empty()) return out;
  AxisDirectionOptions clock;
  clock.period = r.period;
  AxisDirection x(clock), y(clock);
  for (Eigen::Index k = 0; k < r.samples(); ++k) {
    x.step(r.velocity(k, 0));
    y.step(r.velocity(k, 1));
    out[static_cast<std::size_t>(k)] =
        margin_bands.at(r.velocity.row(k).norm(), std::min(x.since_change(), y.since_change()));
  }
  return out;
}

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
  if (!margin_bands.empty()) {
    try {
      margin_bands.validate();
    } catch (const OptionError& e) {
      throw OptionError("margin_bands." + e.field(), e.value(), e.rule());
    }
  }
  if (!(error_exponent > 0.0 && std::isfinite(error_exponent))) {
    throw OptionError("error_exponent", shortest_double(error_exponent), "must be > 0");
  }
  if (!(margin >= 0.0 && std::isfinite(margin))) {
    throw OptionError("margin", shortest_double(margin), "must be >= 0 and finite [mm]");
  }
  if (uniform_steps < 1) {
    throw OptionError("uniform_steps", std::to_string(uniform_steps), "must be >= 1");
  }
  if (!(min_factor > 0.0 && min_factor < 1.0)) {
    throw OptionError("min_factor", shortest_double(min_factor), "must be in (0, 1)");
  }
  if (max_iterations < 1) {
    throw OptionError("max_iterations", std::to_string(max_iterations), "must be >= 1");
  }
  if (!(min_speed > 0.0 && std::isfinite(min_speed))) {
    throw OptionError("min_speed", shortest_double(min_speed), "must be > 0 [mm/s]");
  }
  if (!(standstill_speed >= 0.0 && standstill_speed <= min_speed)) {
    throw OptionError("standstill_speed", shortest_double(standstill_speed),
                      "must be in [0, min_speed " + shortest_double(min_speed) + "] [mm/s]");
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
  const ContourErrorModel model = [&](const ReferenceTrajectory& r) {
    return predict_contour_error(predictor, path, r);
  };
  return optimise_feedrate(path, model, options, progress);
}

namespace {

// max over the ticks (but those at standstill) of predicted + m_k - eps_max
// [mm]: <= 0 within.
double optimisation_worst_excess(const FeedrateOptimisationOptions& o, const ReferenceTrajectory& r,
                                 const std::vector<double>& predicted) {
  const std::vector<double> margins = o.tick_margins(r);
  double worst = -INFINITY;
  for (Eigen::Index k = 0; k < r.samples(); ++k) {
    if (o.at_standstill(r.velocity.row(k).norm())) continue;
    const auto i = static_cast<std::size_t>(k);
    worst = std::max(worst, predicted[i] + margins[i] - o.tolerance);
  }
  return worst;
}

std::vector<double> optimisation_model(const ContourErrorModel& error_model,
                                       const ReferenceTrajectory& r) {
  std::vector<double> predicted = error_model(r);
  if (predicted.size() != static_cast<std::size_t>(r.samples())) {
    throw Error("contour error model returned " + std::to_string(predicted.size()) +
                " values for a reference of " + std::to_string(r.samples()) + " ticks");
  }
  return predicted;
}

// uniform_candidate (feedrate_optimisation.hpp): the largest factor of the
// unconstrained plan the model keeps within the bound; replaces `res` when
// faster (or when the loop found no plan within the bound).
void optimisation_uniform_candidate(const PlanarPath& path, const ContourErrorModel& error_model,
                                    const FeedrateOptimisationOptions& o,
                                    const FeedrateProfile& unconstrained,
                                    FeedrateOptimisationResult& res) {
  struct Trial {
    FeedrateProfile profile;
    ReferenceTrajectory reference;
    std::vector<double> predicted;
  };
  const auto trial = [&](double f) {
    Trial t;
    t.profile = f == 1.0 ? unconstrained : time_scaled(unconstrained, f);
    t.reference = interpolate(path, t.profile, 1e-3);
    t.predicted = optimisation_model(error_model, t.reference);
    return t;
  };
  const auto within = [&](const Trial& t) {
    return optimisation_worst_excess(o, t.reference, t.predicted) <= 0.0;
  };
  Trial best = trial(o.min_factor);
  if (!within(best)) return;  // not even the slowest factor
  double good = o.min_factor, bad = 1.0;
  for (int step = 0; step < o.uniform_steps; ++step) {
    const double mid = 0.5 * (good + bad);
    Trial t = trial(mid);
    if (within(t)) {
      good = mid;
      best = std::move(t);
    } else {
      bad = mid;
    }
  }
  res.uniform_factor = good;
  const bool loop_met = res.status == OptimisationStatus::converged;
  if (loop_met && !(best.profile.total_time() < res.profile.total_time())) return;
  res.uniform_chosen = true;
  res.status = OptimisationStatus::converged;
  res.reason =
      "the uniform slowdown by factor " + shortest_double(good) + " (" +
      fixed_decimals(best.profile.total_time(), 4) +
      " s) keeps the prediction within tolerance - margin " +
      (loop_met ? "faster than local limits (" + fixed_decimals(res.profile.total_time(), 4) + " s)"
                : "where local limits did not (" + res.reason + ")");
  res.profile = std::move(best.profile);
  res.reference = std::move(best.reference);
  res.predicted = std::move(best.predicted);
}

// The loop of feedrate_optimisation.hpp without the uniform candidate.
FeedrateOptimisationResult optimise_feedrate_caps(const PlanarPath& path,
                                                  const ContourErrorModel& error_model,
                                                  const FeedrateOptimisationOptions& options,
                                                  const ProgressCallback& progress,
                                                  FeedrateProfile& unconstrained) {
  FeedratePlannerOptions planner = options.planner;
  planner.speed_cap = {};
  const auto& L = options.planner.limits.axes;
  const double top = std::hypot(L[0].velocity, L[1].velocity);  // no effect as a cap
  FeedrateOptimisationResult res, best;  // best: the fastest plan within bound (raise_caps)
  bool have_best = false;
  std::vector<double> s_knots;
  for (int it = 0; it < options.max_iterations; ++it) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      res.profile = plan_feedrate(path, planner);
    } catch (const Error& e) {
      if (it == 0) throw;  // the unconstrained plan: the path or the limits, not the caps
      // No feasible plan under the lowered caps (Ipopt: a cap too low over
      // too short a span for the jerk limit): the loop ends with what it
      // has, as when a cap falls below min_speed.
      if (have_best) break;
      res.status = OptimisationStatus::infeasible;
      res.reason =
          "no plan under the lowered caps after " + std::to_string(it) + " plan(s): " + e.what();
      return res;
    }
    res.reference = interpolate(path, res.profile, 1e-3);
    res.predicted = optimisation_model(error_model, res.reference);
    if (it == 0) {
      unconstrained = res.profile;
      // Cap knots: the unconstrained grid, at the fastest speed the axis
      // velocity limits allow anywhere (no effect until lowered).
      res.cap = PathSpeedCap::uniform(res.profile.u, top);
      s_knots = optimisation_knot_arc_lengths(path, res.cap.u);
    }
    res.cap = it == 0 ? res.cap : planner.speed_cap;  // the cap this plan was made with
    OptimisationIteration rec;
    rec.worst_predicted = *std::max_element(res.predicted.begin(), res.predicted.end());
    rec.worst_excess = optimisation_worst_excess(options, res.reference, res.predicted);
    rec.time = res.profile.total_time();
    rec.min_cap = *std::min_element(res.cap.speed.begin(), res.cap.speed.end());
    res.history.push_back(rec);
    const bool within = rec.worst_excess <= 0.0;
    if (within && (!have_best || rec.time < best.profile.total_time())) {
      best = res;  // its history is replaced below
      have_best = true;
    }
    if (within && !options.raise_caps) {
      res.status = OptimisationStatus::converged;
      res.reason = "worst predicted contour error " + fixed_decimals(rec.worst_predicted * 1e3, 2) +
                   " um <= tolerance - margin after " + std::to_string(it + 1) + " plan(s)";
      res.history.back().seconds =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      return res;
    }
    PathSpeedCap next = res.cap;
    res.history.back().ticks_over =
        optimisation_lower_caps(options, res.reference, res.predicted, s_knots, top, next);
    res.history.back().seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (progress)
      progress("feedrate optimisation (plans)", res.history.size(),
               static_cast<std::size_t>(options.max_iterations));
    const double lowest = *std::min_element(next.speed.begin(), next.speed.end());
    if (lowest < options.min_speed) {
      if (have_best) break;
      res.status = OptimisationStatus::infeasible;
      res.reason = "the cap would fall to " + shortest_double(lowest) + " mm/s < min_speed " +
                   shortest_double(options.min_speed) +
                   " mm/s: slowing down does not bring the predicted error (worst " +
                   fixed_decimals(rec.worst_predicted * 1e3, 2) + " um) under the tolerance";
      return res;
    }
    double moved = 0.0;  // largest relative change of a knot
    for (std::size_t j = 0; j < next.speed.size(); ++j) {
      moved = std::max(moved, std::abs(next.speed[j] / res.cap.speed[j] - 1.0));
    }
    if (options.raise_caps && have_best && moved < 0.01) break;
    planner.speed_cap = std::move(next);
  }
  if (have_best) {
    const auto history = res.history;
    const double time = best.profile.total_time();
    res = std::move(best);
    res.history = history;
    res.status = OptimisationStatus::converged;
    res.reason =
        "fastest plan within tolerance - margin: " + fixed_decimals(time, 4) +
        " s, worst predicted " +
        fixed_decimals(*std::max_element(res.predicted.begin(), res.predicted.end()) * 1e3, 2) +
        " um, of " + std::to_string(history.size()) + " plan(s)";
    return res;
  }
  res.status = OptimisationStatus::max_iterations;
  res.reason =
      "worst predicted contour error " + shortest_double(res.history.back().worst_predicted * 1e3) +
      " um still above the tolerance after " + std::to_string(res.history.size()) + " plans";
  return res;
}

}  // namespace

FeedrateOptimisationResult optimise_feedrate(const PlanarPath& path,
                                             const ContourErrorModel& error_model,
                                             const FeedrateOptimisationOptions& options,
                                             const ProgressCallback& progress) {
  options.validate();
  FeedrateProfile unconstrained;
  FeedrateOptimisationResult res =
      optimise_feedrate_caps(path, error_model, options, progress, unconstrained);
  if (options.uniform_candidate) {
    optimisation_uniform_candidate(path, error_model, options, unconstrained, res);
  }
  return res;
}

}  // namespace cnclab
