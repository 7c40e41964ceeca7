// Limit refinement (docs/motion.md): between grid nodes the planned motion can
// exceed the limits imposed at the nodes; the planner bisects the grid there
// and replans. Checked here by forward differences of the sampled 1 ms
// positions (difference_peaks.hpp), independent of the planner's own check,
// on a near-cusp turn where the unrefined plan is far over its limits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/limit_check.hpp"
#include "difference_peaks.hpp"
#include "planned_paths.hpp"

namespace cnclab {
namespace {

using testing::difference_peaks;
using testing::DifferencePeaks;

constexpr double kTolerance = 0.005;  // docs/motion.md: every limit within 0.5 %

// Difference peaks divided by the limits, as LimitRatios.
LimitRatios ratios_of(const DifferencePeaks& p, const PlanarLimits& limits) {
  LimitRatios r;
  for (int i = 0; i < 2; ++i) {
    r.velocity[i] = p.v[i] / limits.axes[i].velocity;
    r.acceleration[i] = p.a[i] / limits.axes[i].acceleration;
    r.jerk[i] = p.j[i] / limits.axes[i].jerk;
  }
  return r;
}

LimitRatios difference_ratios(const PlanarPath& path, const FeedrateProfile& profile,
                              const PlanarLimits& limits) {
  const ReferenceTrajectory r = interpolate(path, profile, 1e-3);
  return ratios_of(difference_peaks(r.position, r.period), limits);
}

void print(const char* what, const LimitRatios& r) {
  std::printf("%-30s v %.4f %.4f  a %.4f %.4f  j %.4f %.4f\n", what, r.velocity[0], r.velocity[1],
              r.acceleration[0], r.acceleration[1], r.jerk[0], r.jerk[1]);
}

// A cubic Bézier whose control polygon folds back: a turn of radius 0.195 mm
// at u = 0.504 (|C'| = 6.0 there, mean 54.6 mm per unit u; with P2 = (0, 30)
// it would be a cusp). The whole turn lies inside one 1 mm grid interval.
const CubicBezierPath& near_cusp() {
  static const CubicBezierPath path({Vec2(0, 0), Vec2(30, 30), Vec2(8, 30), Vec2(30, 0)});
  return path;
}

struct Plans {
  FeedrateProfile unrefined, refined;
};

const Plans& near_cusp_plans() {
  static const Plans plans = [] {
    FeedratePlannerOptions off;
    off.refinement.max_rounds = 0;
    return Plans{plan_feedrate(near_cusp(), off), plan_feedrate(near_cusp())};
  }();
  return plans;
}

TEST(LimitRefinement, NearCuspTurnHoldsEveryLimitByDifferences) {
  const PlanarLimits limits;
  const Plans& p = near_cusp_plans();
  const LimitRatios before = difference_ratios(near_cusp(), p.unrefined, limits);
  const LimitRatios after = difference_ratios(near_cusp(), p.refined, limits);
  const LimitRefinementSummary& s = p.refined.refinement;
  print("unrefined, 1 ms differences", before);
  print("refined, 1 ms differences", after);
  std::printf("time %.5f s -> %.5f s (%+.3f %%), %d rounds, %zu local solves, %zu bisected\n",
              p.unrefined.total_time(), p.refined.total_time(),
              100 * (p.refined.total_time() / p.unrefined.total_time() - 1), s.rounds,
              s.local_solves, s.bisected);
  // Not vacuous: without refinement the reference breaks a limit.
  EXPECT_GT(before.worst(), 1 + kTolerance);
  for (int i = 0; i < 2; ++i) {
    EXPECT_LE(after.velocity[i], 1 + kTolerance) << "axis " << i;
    EXPECT_LE(after.acceleration[i], 1 + kTolerance) << "axis " << i;
    EXPECT_LE(after.jerk[i], 1 + kTolerance) << "axis " << i;
  }
  EXPECT_TRUE(s.converged);
  EXPECT_GE(s.rounds, 1);
  EXPECT_LE(s.final.worst(), 1 + kTolerance);
  // The summary's "before" is the unrefined plan.
  EXPECT_NEAR(s.initial_time, p.unrefined.total_time(), 1e-12);
  EXPECT_EQ(p.unrefined.refinement.rounds, 0);
  EXPECT_NEAR(p.unrefined.refinement.initial.worst(), s.initial.worst(), 1e-12);
}

// The planner's check samples the exact derivatives; a forward difference
// averages them over the samples it spans, so it cannot exceed their maximum.
// The checked peaks bound the differences from above (up to the check's
// sampling of 9 instants per interval).
TEST(LimitRefinement, CheckedPeaksBoundTheDifferences) {
  const PlanarLimits limits;
  constexpr double kSamplingSlack = 2e-3;
  const auto expect_bounds = [&](const PlanarPath& path, const FeedrateProfile& profile,
                                 const char* name) {
    const LimitRatios checked = peak_limit_ratios(interval_limit_ratios(path, profile, limits, 8));
    const LimitRatios differences = difference_ratios(path, profile, limits);
    print((std::string(name) + ", checked").c_str(), checked);
    print((std::string(name) + ", differences").c_str(), differences);
    for (int i = 0; i < 2; ++i) {
      EXPECT_GE(checked.velocity[i], differences.velocity[i] * (1 - kSamplingSlack)) << name;
      EXPECT_GE(checked.acceleration[i], differences.acceleration[i] * (1 - kSamplingSlack))
          << name;
      EXPECT_GE(checked.jerk[i], differences.jerk[i] * (1 - kSamplingSlack)) << name;
    }
  };
  expect_bounds(near_cusp(), near_cusp_plans().unrefined, "near cusp, unrefined");
  const testing::PlannedPath& bezier = testing::planned_path("bezier");
  expect_bounds(*bezier.path, bezier.profile, "bezier");
}

// After bisection and local replanning the profile is still one motion: the
// cubic of interval k-1 ends in node k's state (u, du/dt, d2u/dt2).
TEST(LimitRefinement, RefinedProfileIsContinuousAtEveryNode) {
  const FeedrateProfile& f = near_cusp_plans().refined;
  ASSERT_GT(f.u.size(), near_cusp_plans().unrefined.u.size());  // nodes were added
  for (std::size_t k = 1; k < f.u.size(); ++k) {
    const ParameterState s = f.in_interval(k - 1, f.t[k] - f.t[k - 1]);
    ASSERT_NEAR(s.u, f.u[k], 1e-9) << k;
    ASSERT_NEAR(s.ud, f.ud[k], 1e-6 * std::max(1.0, std::abs(f.ud[k]))) << k;
    ASSERT_NEAR(s.udd, f.udd[k], 1e-5 * std::max(1.0, std::abs(f.udd[k]))) << k;
    ASSERT_GT(f.t[k], f.t[k - 1]) << k;
  }
}

TEST(LimitRefinement, BadOptionsNameTheField) {
  const LinePath line(Vec2(0, 0), Vec2(100, 0));
  const auto field = [&](auto change) {
    FeedratePlannerOptions o;
    change(o.refinement);
    try {
      plan_feedrate(line, o);
    } catch (const OptionError& e) {
      return e.field();
    }
    return std::string("(no error)");
  };
  EXPECT_EQ(field([](LimitRefinementOptions& r) { r.tolerance = 0; }), "refinement.tolerance");
  EXPECT_EQ(field([](LimitRefinementOptions& r) { r.tolerance = 0.6; }), "refinement.tolerance");
  EXPECT_EQ(field([](LimitRefinementOptions& r) { r.max_rounds = -1; }), "refinement.max_rounds");
  EXPECT_EQ(field([](LimitRefinementOptions& r) { r.samples = 0; }), "refinement.samples");
}

}  // namespace
}  // namespace cnclab
