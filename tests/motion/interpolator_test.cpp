// The 1 ms reference differentiated numerically: every axis limit holds
// within 0.5 % (docs/motion.md), and the analytic derivatives agree with the
// differences.
#include "cnclab/motion/interpolator.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numbers>

#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "difference_peaks.hpp"
#include "planned_paths.hpp"

namespace cnclab {
namespace {

// The limits hold within 0.5 % on the 1 ms reference (the planner
// refines its grid where they would not, feedrate_planner.hpp).
constexpr double kInterpolatorLimitTolerance = 0.005;

using testing::difference_peaks;
using testing::DifferencePeaks;

TEST(Interpolator, NumericalDerivativesRespectEveryLimit) {
  const PlanarLimits limits;
  for (const char* name : testing::kPlannedPathNames) {
    const testing::PlannedPath& planned = testing::planned_path(name);
    const PlanarPath* path = planned.path.get();
    const ReferenceTrajectory r = interpolate(*path, planned.profile, 1e-3);
    const DifferencePeaks peaks = difference_peaks(r.position, r.period);
    std::printf("%-12s peak |v| %6.1f %6.1f  |a| %7.1f %7.1f  |j| %8.0f %8.0f  (%ld samples)\n",
                name, peaks.v[0], peaks.v[1], peaks.a[0], peaks.a[1], peaks.j[0], peaks.j[1],
                static_cast<long>(r.samples()));
    for (int i = 0; i < 2; ++i) {
      EXPECT_LE(peaks.v[i], limits.axes[i].velocity * (1 + kInterpolatorLimitTolerance));
      EXPECT_LE(peaks.a[i], limits.axes[i].acceleration * (1 + kInterpolatorLimitTolerance));
      EXPECT_LE(peaks.j[i], limits.axes[i].jerk * (1 + kInterpolatorLimitTolerance));
    }
    // Ends: starts and stops at the path's ends.
    EXPECT_LT((r.position.row(0).transpose() - path->evaluate(path->u_begin()).position).norm(),
              1e-9);
    EXPECT_LT((r.position.row(r.samples() - 1).transpose() - path->evaluate(path->u_end()).position)
                  .norm(),
              1e-6);
  }
}

TEST(Interpolator, AnalyticDerivativesMatchDifferences) {
  const testing::PlannedPath& bezier = testing::planned_path("bezier");
  const ReferenceTrajectory r = interpolate(*bezier.path, bezier.profile, 1e-3);
  const double h = r.period;
  double v_err = 0, a_err = 0;
  for (Eigen::Index k = 1; k + 1 < r.samples(); ++k) {
    const Vec2 v = (r.position.row(k + 1) - r.position.row(k - 1)).transpose() / (2 * h);
    const Vec2 a = (r.velocity.row(k + 1) - r.velocity.row(k - 1)).transpose() / (2 * h);
    v_err = std::max(v_err, (v - r.velocity.row(k).transpose()).norm());
    a_err = std::max(a_err, (a - r.acceleration.row(k).transpose()).norm());
  }
  // Central-difference error ~ h^2 |q'''| / 6 = 1e-6 * 5e4 / 6 = 0.008 mm/s;
  // for the acceleration h^2 |q''''|/6 plus the jerk steps: a few mm/s^2.
  EXPECT_LT(v_err, 0.05);
  EXPECT_LT(a_err, 50.0);
}

TEST(Interpolator, DifferentLimitsPerAxis) {
  // A slower y axis (half the x limits): each axis keeps its own limits.
  const testing::PlannedPath& bezier = testing::planned_path("bezier");
  FeedratePlannerOptions options;
  options.limits.axes[1] = {150.0, 1000.0, 25000.0};
  const ReferenceTrajectory r =
      interpolate(*bezier.path, plan_feedrate(*bezier.path, options), 1e-3);
  const DifferencePeaks peaks = difference_peaks(r.position, r.period);
  std::printf("y at half limits: peak |v| %.1f %.1f  |a| %.0f %.0f  |j| %.0f %.0f\n", peaks.v[0],
              peaks.v[1], peaks.a[0], peaks.a[1], peaks.j[0], peaks.j[1]);
  for (int i = 0; i < 2; ++i) {
    const AxisLimits& L = options.limits.axes[i];
    EXPECT_LE(peaks.v[i], L.velocity * (1 + kInterpolatorLimitTolerance));
    EXPECT_LE(peaks.a[i], L.acceleration * (1 + kInterpolatorLimitTolerance));
    EXPECT_LE(peaks.j[i], L.jerk * (1 + kInterpolatorLimitTolerance));
  }
  // The y limits bind somewhere (within 5 %), so the test is not vacuous.
  EXPECT_GT(std::max({peaks.v[1] / 150.0, peaks.a[1] / 1000.0, peaks.j[1] / 25000.0}), 0.95);
}

}  // namespace
}  // namespace cnclab
