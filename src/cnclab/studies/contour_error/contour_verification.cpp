#include "cnclab/studies/contour_error/contour_verification.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/motion/constant_feed_reference.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "cnclab/motion/feedrate_bounds.hpp"

namespace cnclab {
namespace {

// Bisection on a parameter p in [lo, hi] for the largest p whose reference
// meets the tolerance (met at small p, failed at large p assumed).
BaselineResult verification_bisect(const std::string& method, double lo, double hi,
                                   const PlanarPath& path, const VerificationOptions& o,
                                   const std::function<ReferenceTrajectory(double)>& make) {
  BaselineResult res;
  res.method = method;
  auto attempt = [&](double p, BaselineResult& into) {
    into.parameter = p;
    into.reference = make(p);
    into.check = check_on_machine(path, into.reference, o);
    return into.check.met;
  };
  if (attempt(hi, res)) {
    res.met = true;
    res.reason = "met at the fastest setting";
    return res;
  }
  BaselineResult best;
  if (!attempt(lo, best)) {
    best.method = method;
    best.reason = "not met even at " + shortest_double(lo) + ": share within " +
                  shortest_double(best.check.share_within) + ", max " +
                  shortest_double(best.check.max * 1e3) + " um";
    return best;
  }
  double good = lo, bad = hi;
  for (int step = 0; step < o.bisection_steps; ++step) {
    const double mid = 0.5 * (good + bad);
    BaselineResult trial;
    if (attempt(mid, trial)) {
      good = mid;
      best = std::move(trial);
    } else {
      bad = mid;
    }
  }
  best.method = method;
  best.met = true;
  best.reason =
      "bisection: met at " + shortest_double(good) + ", failed at " + shortest_double(bad);
  return best;
}

}  // namespace

void VerificationOptions::validate() const {
  try {
    machine.validate();
  } catch (const OptionError& e) {
    throw OptionError("machine." + e.field(), e.value(), e.rule());
  }
  if (!(tolerance > 0.0 && std::isfinite(tolerance))) {
    throw OptionError("tolerance", shortest_double(tolerance), "must be > 0 [mm]");
  }
  if (!(required_share > 0.0 && required_share <= 1.0)) {
    throw OptionError("required_share", shortest_double(required_share), "must be in (0, 1]");
  }
  if (bisection_steps < 1) {
    throw OptionError("bisection_steps", std::to_string(bisection_steps), "must be >= 1");
  }
  if (!(min_factor > 0.0 && min_factor < 1.0)) {
    throw OptionError("min_factor", shortest_double(min_factor), "must be in (0, 1)");
  }
}

ContourCheck check_on_machine(const PlanarPath& path, const ReferenceTrajectory& reference,
                              const VerificationOptions& options) {
  const MachineResponse m = simulate_machine(options.machine, reference, options.seed);
  ContourCheck c;
  c.simulated.resize(static_cast<std::size_t>(reference.samples()));
  std::size_t within = 0;
  for (Eigen::Index k = 0; k < reference.samples(); ++k) {
    const double d =
        project_to_path(path, m.actual.row(k).transpose(), reference.u[static_cast<std::size_t>(k)])
            .distance;
    c.simulated[static_cast<std::size_t>(k)] = d;
    c.max = std::max(c.max, d);
    if (d <= options.tolerance) ++within;
  }
  c.share_within = static_cast<double>(within) / static_cast<double>(reference.samples());
  c.time = reference.time.back();
  c.met = c.share_within >= options.required_share;
  return c;
}

BaselineResult uniform_slowdown(const PlanarPath& path, const FeedrateProfile& unconstrained,
                                const VerificationOptions& options) {
  options.validate();
  const double period = options.machine.timing.controller_period;
  return verification_bisect(
      "uniform_slowdown", options.min_factor, 1.0, path, options,
      [&](double f) { return interpolate(path, time_scaled(unconstrained, f), period); });
}

BaselineResult constant_feed(const PlanarPath& path, const PlanarLimits& limits,
                             const VerificationOptions& options) {
  options.validate();
  const double period = options.machine.timing.controller_period;
  const double best = constant_feedrate_time(path, limits).feedrate;
  return verification_bisect("constant_feed", options.min_factor * best, best, path, options,
                             [&](double feed) {
                               return constant_feed_reference(
                                   path, constant_feedrate_time(path, limits, 20001, feed), period);
                             });
}

}  // namespace cnclab
