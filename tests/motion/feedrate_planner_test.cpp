#include "cnclab/motion/feedrate_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/feedrate_bounds.hpp"
#include "cnclab/motion/scurve.hpp"
#include "planned_paths.hpp"

namespace cnclab {
namespace {

constexpr double kSCurveTolerance = 0.005;  // docs/motion.md: within 0.5 %

TEST(FeedratePlanner, StraightLineMatchesSCurve) {
  // Lines along x, at 30 degrees (x axis binds: path limits = axis / cos 30),
  // and short (peak velocity not reached), two of them longer than a window.
  for (const Vec2& end : {Vec2(200, 0), Vec2(173.2050808, 100), Vec2(15, 0)}) {
    const LinePath line(Vec2(0, 0), end);
    const double c = std::max(std::abs(end.x()), std::abs(end.y())) / end.norm();
    const double expected = scurve_time(end.norm(), 300 / c, 2000 / c, 50000 / c);
    const FeedrateProfile p = plan_feedrate(line);
    std::printf("line to (%.1f, %.1f): planned %.5f s, S-curve %.5f s, %zu windows\n", end.x(),
                end.y(), p.total_time(), expected, p.windows.size());
    EXPECT_NEAR(p.total_time(), expected, kSCurveTolerance * expected);
  }
}

}  // namespace
}  // namespace cnclab

namespace cnclab {
namespace {

// Planned time between the v+a-only lower bound and the constant-feedrate
// upper bound on curved paths; all three printed.
TEST(FeedratePlanner, PlannedTimeLiesBetweenIndependentBounds) {
  for (const char* name : testing::kPlannedPathNames) {
    const testing::PlannedPath& p = testing::planned_path(name);
    const double lower = velocity_acceleration_time(*p.path, PlanarLimits{});
    const ConstantFeedrateProfile upper = constant_feedrate_time(*p.path, PlanarLimits{});
    const double planned = p.profile.total_time();
    std::printf(
        "%-12s lower (v,a only) %.4f s <= planned %.4f s <= constant feedrate %.4f s "
        "(F = %.1f mm/s)\n",
        name, lower, planned, upper.time, upper.feedrate);
    EXPECT_LT(lower, planned) << name;
    // On a line the upper bound is the S-curve itself: allow the planner's
    // discretisation error there.
    EXPECT_LT(planned, upper.time * (1 + kSCurveTolerance)) << name;
  }
}

TEST(FeedratePlanner, BoundsOnALineAreClosedForms) {
  // Along x: the v+a-only time is the trapezoid L/V + V/A; the upper bound
  // is the S-curve.
  const LinePath line(Vec2(0, 0), Vec2(100, 0));
  EXPECT_NEAR(velocity_acceleration_time(line, PlanarLimits{}), 100.0 / 300 + 300.0 / 2000, 1e-9);
  EXPECT_NEAR(constant_feedrate_time(line, PlanarLimits{}).time, scurve_time(100, 300, 2000, 50000),
              1e-9);
}

TEST(FeedratePlanner, RejectsBadOptionsAndCusps) {
  const LinePath line(Vec2(0, 0), Vec2(100, 0));
  FeedratePlannerOptions o;
  o.limits.axes[1].jerk = 0;
  EXPECT_THROW(plan_feedrate(line, o), OptionError);
  try {
    plan_feedrate(line, o);
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "limits.axes[1].jerk");
  }
  o = {};
  o.limits.axes[0].velocity = std::nan("");
  EXPECT_THROW(plan_feedrate(line, o), OptionError);
  o = {};
  o.window_intervals = 240;
  o.commit_intervals = 205;  // overlap 35 mm < stopping distance 40 mm
  EXPECT_THROW(plan_feedrate(line, o), OptionError);
  // A cubic with a cusp: control polygon folded back on itself (C'(1/2) = 0).
  const CubicBezierPath cusp({Vec2(0, 0), Vec2(30, 30), Vec2(0, 30), Vec2(30, 0)});
  try {
    plan_feedrate(cusp);
    ADD_FAILURE() << "expected an error for a cusp";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cusp"), std::string::npos) << e.what();
    const std::string m = e.what();
    const std::size_t at = m.find("at u = ");
    ASSERT_NE(at, std::string::npos) << m;
    EXPECT_NEAR(std::stod(m.substr(at + 7)), 0.5, 1e-3) << m;
  }
}

TEST(FeedratePlanner, IpoptFailureNamesTheWindow) {
  // One Ipopt iteration cannot converge: the error names window, nodes and status.
  const LinePath line(Vec2(0, 0), Vec2(100, 0));
  FeedratePlannerOptions o;
  o.max_iterations = 1;
  try {
    plan_feedrate(line, o);
    ADD_FAILURE() << "expected an Ipopt failure";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("window 1 of"), std::string::npos) << m;
    EXPECT_NE(m.find("Maximum_Iterations_Exceeded"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace cnclab

namespace cnclab {
namespace {

TEST(FeedratePlanner, WindowsMatchOneWindowAndJoinContinuously) {
  const testing::PlannedPath& p = testing::planned_path("bezier");
  ASSERT_GE(p.profile.windows.size(), 2u);
  FeedratePlannerOptions one;
  one.window_intervals = 2000;
  one.commit_intervals = 1000;
  const FeedrateProfile single = plan_feedrate(*p.path, one);
  ASSERT_EQ(single.windows.size(), 1u);
  std::printf("bezier: %zu windows %.5f s, one window %.5f s\n", p.profile.windows.size(),
              p.profile.total_time(), single.total_time());
  EXPECT_NEAR(p.profile.total_time(), single.total_time(), 1e-3 * single.total_time());
  // At each window junction the state (u, du/dt, d2u/dt2) reached by the
  // left interval's cubic is the right interval's start state.
  const FeedrateProfile& f = p.profile;
  for (std::size_t w = 1; w < f.windows.size(); ++w) {
    const std::size_t k = f.windows[w].first_node;
    const double h = f.t[k] - f.t[k - 1], j = f.uddd[k - 1];
    const double u = f.u[k - 1] + f.ud[k - 1] * h + f.udd[k - 1] * h * h / 2 + j * h * h * h / 6;
    const double ud = f.ud[k - 1] + f.udd[k - 1] * h + j * h * h / 2;
    const double udd = f.udd[k - 1] + j * h;
    EXPECT_NEAR(u, f.u[k], 1e-9);
    EXPECT_NEAR(ud, f.ud[k], 1e-7 * std::abs(f.ud[k]));
    EXPECT_NEAR(udd, f.udd[k], 1e-6 * std::max(1.0, std::abs(f.udd[k])));
  }
}

}  // namespace
}  // namespace cnclab
