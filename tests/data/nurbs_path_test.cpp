#include "cnclab/data/nurbs_path.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/feedrate_bounds.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

RandomNurbsPathOptions small_options() {
  RandomNurbsPathOptions o;
  o.degree = 4;
  o.control_points = 8;
  o.x_max = 150.0;
  o.y_max = 120.0;
  o.weight_min = 0.5;
  o.weight_max = 2.0;
  return o;
}

// C', C'', C''' of the adapter against central differences of C, C', C''
// (away from knots, where a curve's C''' may jump).
TEST(NurbsPlanarPath, DerivativesMatchCentralDifferences) {
  Rng rng(21, "nurbs_path");
  for (int degree : {3, 4, 5}) {
    RandomNurbsPathOptions o = small_options();
    o.degree = degree;
    const NurbsPlanarPath path(random_planar_nurbs(o, rng));
    EXPECT_EQ(path.u_begin(), 0.0);
    EXPECT_EQ(path.u_end(), 1.0);
    const double h = 1e-6;
    for (int k = 1; k < 40; ++k) {
      const double u = (k + 0.37) / 41.0;
      const PathPoint p = path.evaluate(u), plus = path.evaluate(u + h),
                      minus = path.evaluate(u - h);
      const Eigen::Vector3d point = curve_point(path.curve(), u);
      EXPECT_NEAR((p.position - point.head<2>()).norm(), 0.0, 1e-10);
      EXPECT_NEAR((p.d1 - (plus.position - minus.position) / (2 * h)).norm(), 0.0,
                  1e-6 * (1 + p.d1.norm()));
      EXPECT_NEAR((p.d2 - (plus.d1 - minus.d1) / (2 * h)).norm(), 0.0, 1e-6 * (1 + p.d2.norm()));
      EXPECT_NEAR((p.d3 - (plus.d2 - minus.d2) / (2 * h)).norm(), 0.0, 1e-5 * (1 + p.d3.norm()))
          << degree << " " << u;
    }
  }
}

TEST(NurbsPlanarPath, RejectsANonPlanarCurve) {
  Rng rng(3);
  NurbsCurve c = random_planar_nurbs(small_options(), rng);
  c.points[2].z() = 0.5;
  const std::string m = testing::error_message<OptionError>([&] { NurbsPlanarPath p(c); });
  EXPECT_NE(m.find("[2].z = 0.5: a planar path needs z = 0"), std::string::npos) << m;
}

TEST(RandomNurbsPath, SameSeedSameCurveInsideTheWorkArea) {
  const RandomNurbsPathOptions o = small_options();
  Rng a(5, "nurbs_path"), b(5, "nurbs_path"), c(6, "nurbs_path");
  const NurbsCurve ca = random_planar_nurbs(o, a), cb = random_planar_nurbs(o, b),
                   cc = random_planar_nurbs(o, c);
  ASSERT_EQ(ca.points.size(), o.control_points);
  EXPECT_EQ(ca.knots, cb.knots);
  EXPECT_EQ(ca.weights, cb.weights);
  bool differs = false;
  for (std::size_t i = 0; i < ca.points.size(); ++i) {
    EXPECT_EQ(ca.points[i], cb.points[i]);
    differs = differs || ca.points[i] != cc.points[i];
    EXPECT_GE(ca.points[i].x(), o.x_min);
    EXPECT_LT(ca.points[i].x(), o.x_max);
    EXPECT_GE(ca.points[i].y(), o.y_min);
    EXPECT_LT(ca.points[i].y(), o.y_max);
    EXPECT_GE(ca.weights[i], o.weight_min);
    EXPECT_LT(ca.weights[i], o.weight_max);
  }
  EXPECT_TRUE(differs);
  // Clamped, uniform interior knots on [0, 1]: 8 points, degree 4 -> 4 spans.
  EXPECT_EQ(ca.knots, (std::vector<double>{0, 0, 0, 0, 0, 0.25, 0.5, 0.75, 1, 1, 1, 1, 1}));
}

TEST(RandomNurbsPath, CuspIsAClearError) {
  // The motion cusp check is applied to every drawn curve: with its
  // threshold at 0.99 x the mean parametric speed every curve fails it (no
  // curve of uneven steps keeps |C'| that constant) and the error says why.
  RandomNurbsPathOptions o = small_options();
  o.regularity.min_speed_ratio = 0.99;
  o.control_points = 12;
  o.max_attempts = 3;
  Rng rng(1);
  const std::string m = testing::error_message<Error>([&] { random_planar_nurbs(o, rng); });
  EXPECT_NE(m.find("random NURBS path (degree 4, 12 control points): no curve of 3 attempts "
                   "passed; last: path has a cusp or stationary point at u = "),
            std::string::npos)
      << m;
}

// Every returned curve honours min_curvature_radius (checked here on an
// independent finer grid through the closed form of seed 002 Eq. 5), and an
// unreachable radius is a clear error.
TEST(RandomNurbsPath, CurvatureRadiusBound) {
  RandomNurbsPathOptions o = small_options();
  o.min_curvature_radius = 3.0;
  Rng rng(9);
  for (int trial = 0; trial < 5; ++trial) {
    const NurbsPlanarPath path(random_planar_nurbs(o, rng));
    double min_radius = 1e300;
    for (int k = 0; k <= 100000; ++k) {
      const PathPoint p = path.evaluate(k / 100000.0);
      const double cross = std::abs(p.d1.x() * p.d2.y() - p.d1.y() * p.d2.x());
      min_radius = std::min(min_radius, std::pow(p.d1.norm(), 3) / cross);
    }
    EXPECT_GT(min_radius, 0.99 * o.min_curvature_radius) << trial;
  }
  o.min_curvature_radius = 1e6;  // larger than the work area: impossible
  o.max_attempts = 2;
  const std::string m = testing::error_message<Error>([&] { random_planar_nurbs(o, rng); });
  EXPECT_NE(m.find("no curve of 2 attempts passed; last: radius of curvature "), std::string::npos)
      << m;
  EXPECT_NE(m.find("is below min_curvature_radius = 1000000 mm"), std::string::npos) << m;
}

TEST(RandomNurbsPath, ValidationNamesTheField) {
  const auto message = [](auto change) {
    RandomNurbsPathOptions o;
    change(o);
    return testing::error_message<OptionError>([&] { o.validate(); });
  };
  EXPECT_EQ(message([](RandomNurbsPathOptions&) {}), "no error");
  EXPECT_NE(message([](auto& o) { o.degree = 0; }).find("degree = 0"), std::string::npos);
  EXPECT_NE(message([](auto& o) { o.control_points = 4; }).find("must be >= degree + 1 = 5"),
            std::string::npos);
  EXPECT_NE(message([](auto& o) { o.x_max = -1; }).find("x_min, x_max = 0, -1"), std::string::npos);
  EXPECT_NE(message([](auto& o) { o.y_max = NAN; }).find("y_min, y_max"), std::string::npos);
  EXPECT_NE(message([](auto& o) { o.weight_min = 0; }).find("weight_min, weight_max = 0, 1"),
            std::string::npos);
  EXPECT_NE(message([](auto& o) { o.min_curvature_radius = -1; }).find("min_curvature_radius = -1"),
            std::string::npos);
  EXPECT_NE(message([](auto& o) { o.max_attempts = 0; }).find("max_attempts = 0"),
            std::string::npos);
  EXPECT_NE(message([](auto& o) { o.regularity.samples = 1; }).find("regularity.samples = 1"),
            std::string::npos);
}

// A short random trajectory planned with the Ipopt planner at seed 002's
// limits: the planned time lies between the independent bounds, and the 1 ms
// reference respects every axis limit within 1 % (the degree-4 path has a
// continuous C''', so the jerk limit holds between grid nodes too).
TEST(RandomNurbsPath, PlansWithinTheLimits) {
  Rng rng(2026, "nurbs_path");
  RandomNurbsPathOptions o = small_options();
  o.control_points = 6;
  const NurbsPlanarPath path(random_planar_nurbs(o, rng));
  const PlanarLimits limits;
  const FeedrateProfile profile = plan_feedrate(path);
  const double lower = velocity_acceleration_time(path, limits);
  const double upper = constant_feedrate_time(path, limits).time;
  std::printf(
      "random NURBS (%.1f mm): lower %.4f s <= planned %.4f s <= constant feedrate %.4f s\n",
      arc_length(path), lower, profile.total_time(), upper);
  EXPECT_LT(lower, profile.total_time());
  EXPECT_LT(profile.total_time(), upper);
  const ReferenceTrajectory r = interpolate(path, profile);
  // Divided differences of the 1 ms positions (independent of the
  // interpolator's analytic derivatives).
  const double T = r.period;
  for (int axis = 0; axis < 2; ++axis) {
    const AxisLimits& l = limits.axes[static_cast<std::size_t>(axis)];
    const Eigen::VectorXd x = r.position.col(axis);
    double v = 0, a = 0, j = 0;
    for (Eigen::Index k = 0; k + 3 < x.size(); ++k) {
      v = std::max(v, std::abs(x[k + 1] - x[k]) / T);
      a = std::max(a, std::abs(x[k + 2] - 2 * x[k + 1] + x[k]) / (T * T));
      j = std::max(j, std::abs(x[k + 3] - 3 * x[k + 2] + 3 * x[k + 1] - x[k]) / (T * T * T));
    }
    std::printf("axis %d: max |v| %.2f mm/s, |a| %.1f mm/s^2, |j| %.0f mm/s^3\n", axis, v, a, j);
    EXPECT_LE(v, 1.01 * l.velocity) << axis;
    EXPECT_LE(a, 1.01 * l.acceleration) << axis;
    EXPECT_LE(j, 1.01 * l.jerk) << axis;
  }
  EXPECT_NEAR((r.position.row(r.samples() - 1).transpose() - path.evaluate(1.0).position).norm(),
              0.0, 1e-6);
}

}  // namespace
}  // namespace cnclab
