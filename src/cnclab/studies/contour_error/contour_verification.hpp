#pragma once
// Verification of a planned reference on the simulated machine and the two
// baselines of the contour-error feedrate optimisation (docs/motion.md): the
// uniform slowdown of the unconstrained plan (a feed override, found by
// bisection) and the best constant feed (a constant-feed S-curve, bisection
// on the feed), both judged by the simulated contour error.
#include <cstdint>
#include <string>
#include <vector>

#include "cnclab/motion/axis_limits.hpp"
#include "cnclab/motion/feedrate_profile.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/machine.hpp"
#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

struct VerificationOptions {
  MachineOptions machine;    // the simulated machine (the predictor's training machine)
  std::uint64_t seed = 1;    // its scale-noise streams (simulate_machine)
  double tolerance = 0.005;  // eps_max [mm]
  // A reference meets the tolerance when at least this share of its ticks
  // has a simulated contour error <= eps_max (the study's target: 99.9 %). In (0, 1].
  double required_share = 0.999;
  // Bisection steps of the baselines (factor or feed), >= 1; 12 halve the
  // bracket to 1/4096 of its width.
  int bisection_steps = 12;
  // Smallest slowdown factor / share of the best constant feed tried; a
  // baseline that fails even there is reported as not met. In (0, 1).
  double min_factor = 0.02;

  void validate() const;  // OptionError naming the field
};

// The simulated contour error of one reference.
struct ContourCheck {
  std::vector<double> simulated;  // exact |P - path| per tick, P the tool position [mm]
  double max = 0.0;               // [mm]
  double share_within = 0.0;      // ticks with simulated <= eps_max / ticks
  double time = 0.0;              // traversal time: last tick's time [s]
  bool met = false;               // share_within >= required_share
};

// Runs the machine on `reference` and projects every tool position on the
// path (project_to_path from the reference's u).
ContourCheck check_on_machine(const PlanarPath& path, const ReferenceTrajectory& reference,
                              const VerificationOptions& options);

struct BaselineResult {
  std::string method;      // "uniform_slowdown" | "constant_feed"
  double parameter = 0.0;  // slowdown factor f, or the cruise feed F [mm/s]
  ContourCheck check;      // of the fastest reference found that meets the tolerance
  ReferenceTrajectory reference;
  bool met = false;  // false: even the slowest one tried fails (check is that one's)
  std::string reason;
};

// Largest f in [min_factor, 1] with time_scaled(unconstrained, f) meeting the
// tolerance, by bisection (the simulated error is taken to fall as f does).
BaselineResult uniform_slowdown(const PlanarPath& path, const FeedrateProfile& unconstrained,
                                const VerificationOptions& options);

// Largest cruise feed F in [min_factor F_best, F_best] whose best constant-feed
// S-curve (constant_feedrate_time with max_feed F, constant_feed_reference)
// meets the tolerance; F_best the fastest the axis limits allow.
BaselineResult constant_feed(const PlanarPath& path, const PlanarLimits& limits,
                             const VerificationOptions& options);

}  // namespace cnclab
