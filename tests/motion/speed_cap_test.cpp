// The path-speed cap of the feedrate planner, the uniform time scaling of a
// profile and the constant-feed S-curve reference, each against a closed
// form or a second computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/constant_feed_reference.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/path_speed_cap.hpp"
#include "cnclab/motion/scurve.hpp"

namespace cnclab {
namespace {

constexpr double kPlanTolerance = 0.005;  // planner vs S-curve on a line (docs/motion.md)
// Between nodes the cubic motion may exceed a cap imposed at the nodes: where
// the cap binds the plan rides it node to node with alternating path
// acceleration (measured: 42.96 mm/s on a 40 mm/s cap at the 1 mm grid, 7.4 %).
constexpr double kCapExcess = 0.08;

TEST(PathSpeedCap, InterpolatesLinearlyAndValidates) {
  PathSpeedCap cap{{0.0, 1.0, 2.0}, {100.0, 50.0, 50.0}};
  EXPECT_DOUBLE_EQ(cap.at(-1.0), 100.0);
  EXPECT_DOUBLE_EQ(cap.at(0.5), 75.0);
  EXPECT_DOUBLE_EQ(cap.at(3.0), 50.0);
  EXPECT_TRUE(std::isinf(PathSpeedCap{}.at(0.3)));
  cap.speed[1] = 0.0;
  EXPECT_THROW(cap.validate(), OptionError);
  cap.speed[1] = 1.0;
  cap.u[2] = 1.0;
  EXPECT_THROW(cap.validate(), OptionError);
}

// A uniform cap F on a line is a line with a lower velocity limit: the
// planned time is the S-curve's with v_max = F.
TEST(PathSpeedCap, UniformCapOnALineIsTheSCurve) {
  const LinePath line(Vec2(0, 0), Vec2(120, 0));
  FeedratePlannerOptions o;
  o.speed_cap = PathSpeedCap::uniform({0.0, 1.0}, 100.0);
  const FeedrateProfile p = plan_feedrate(line, o);
  const double expected = scurve_time(120.0, 100.0, 2000.0, 50000.0);
  EXPECT_NEAR(p.total_time(), expected, kPlanTolerance * expected);
}

// A local cap slows the path there: it holds at every grid node, and between
// nodes where the cap is flat (it is imposed at nodes only; a cap ramping
// within one grid interval is seen at its ends).
TEST(PathSpeedCap, LocalCapHoldsOnTheReference) {
  const CirclePath arc(Vec2(0, 0), 30.0, 0.0, 3.0);
  const FeedrateProfile free = plan_feedrate(arc);
  FeedratePlannerOptions o;
  o.speed_cap = {{0.0, 0.4, 0.45, 0.6, 0.65, 1.0}, {1e3, 1e3, 40.0, 40.0, 1e3, 1e3}};
  const FeedrateProfile capped = plan_feedrate(arc, o);
  EXPECT_GT(capped.total_time(), free.total_time());
  for (std::size_t k = 0; k < capped.u.size(); ++k) {
    const double speed = arc.evaluate(capped.u[k]).d1.norm() * capped.ud[k];
    EXPECT_LE(speed, o.speed_cap.at(capped.u[k]) * (1 + 1e-6)) << "node u " << capped.u[k];
  }
  const ReferenceTrajectory r = interpolate(arc, capped);
  for (Eigen::Index k = 0; k < r.samples(); ++k) {
    if (r.u[k] < 0.462 || r.u[k] > 0.588) continue;  // one grid interval (1.1e-2) inside
    EXPECT_LE(r.velocity.row(k).norm(), 40.0 * (1 + kCapExcess)) << "u " << r.u[k];
  }
}

TEST(TimeScaled, VelocitiesScaleByTheFactor) {
  const CirclePath arc(Vec2(0, 0), 20.0, 0.0, 2.0);
  const FeedrateProfile p = plan_feedrate(arc);
  constexpr double f = 0.5;
  const FeedrateProfile slow = time_scaled(p, f);
  EXPECT_NEAR(slow.total_time(), p.total_time() / f, 1e-12);
  const ReferenceTrajectory a = interpolate(arc, p), b = interpolate(arc, slow);
  for (Eigen::Index k = 0; 2 * k < b.samples() && k < a.samples(); k += 7) {
    EXPECT_NEAR((b.position.row(2 * k) - a.position.row(k)).norm(), 0.0, 1e-9);
    EXPECT_NEAR((b.velocity.row(2 * k) - f * a.velocity.row(k)).norm(), 0.0, 1e-9);
  }
  EXPECT_THROW(time_scaled(p, 0.0), OptionError);
  EXPECT_THROW(time_scaled(p, 1.5), OptionError);
}

// The state integrates to the distance at scurve_time and the speed is the
// derivative of the distance (central differences).
TEST(ScurveState, ReachesTheDistanceAndIsConsistent) {
  for (double distance : {200.0, 15.0, 0.5}) {
    const double T = scurve_time(distance, 300, 2000, 50000);
    const ScurveState end = scurve_state(distance, 300, 2000, 50000, T);
    EXPECT_NEAR(end.s, distance, 1e-9 * distance + 1e-12);
    EXPECT_NEAR(end.v, 0.0, 1e-6);
    double v_peak = 0.0;
    constexpr double h = 1e-6;
    for (int i = 1; i < 200; ++i) {
      const double t = T * i / 200.0;
      const ScurveState st = scurve_state(distance, 300, 2000, 50000, t);
      const double ds = (scurve_state(distance, 300, 2000, 50000, t + h).s -
                         scurve_state(distance, 300, 2000, 50000, t - h).s) /
                        (2 * h);
      EXPECT_NEAR(st.v, ds, 1e-4 * (1 + st.v));
      EXPECT_LE(std::abs(st.a), 2000 * (1 + 1e-9));
      v_peak = std::max(v_peak, st.v);
    }
    EXPECT_LE(v_peak, 300 * (1 + 1e-9));
  }
}

// On a circle the constant-feed reference runs on the circle at the S-curve
// speed: |q'| = v(t), |q| = r, and it ends at the path end at rest.
TEST(ConstantFeedReference, FollowsTheSCurveOnACircle) {
  const CirclePath arc(Vec2(0, 0), 25.0, 0.0, 2.5);
  const ConstantFeedrateProfile c{0.0, 80.0, 500.0, 20000.0};
  const ReferenceTrajectory r = constant_feed_reference(arc, c);
  const double L = 25.0 * 2.5;
  EXPECT_NEAR(r.time.back(), std::ceil(scurve_time(L, 80, 500, 20000) / 1e-3 - 1e-9) * 1e-3, 1e-12);
  for (Eigen::Index k = 0; k < r.samples(); k += 5) {
    const ScurveState st = scurve_state(L, 80, 500, 20000, r.time[k]);
    EXPECT_NEAR(r.position.row(k).norm(), 25.0, 1e-9);
    EXPECT_NEAR(r.velocity.row(k).norm(), st.v, 1e-6 * (1 + st.v));
    // Arc length from the start: the angle of the position times r.
    const double angle = std::atan2(r.position(k, 1), r.position(k, 0));
    const double s = 25.0 * (angle < -1e-9 ? angle + 2 * M_PI : angle);
    EXPECT_NEAR(s, st.s, 1e-6);
  }
  const Eigen::Index n = r.samples() - 1;
  EXPECT_NEAR(r.position(n, 0), 25.0 * std::cos(2.5), 1e-9);
  EXPECT_NEAR(r.velocity.row(n).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace cnclab
