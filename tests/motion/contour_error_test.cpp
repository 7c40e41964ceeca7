// Contour errors on circles, where the exact value is ||P - c| - r|.
#include "cnclab/motion/contour_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "cnclab/core/rng.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/machine.hpp"
#include "planned_paths.hpp"

namespace cnclab {
namespace {

constexpr double kPi = std::numbers::pi;

// A point near the circle and a reference parameter that leads or lags it
// by up to `lag` mm of arc, as a following error would.
struct Sample {
  Vec2 actual;
  double u_ref;
};
Sample near_circle(Rng& rng, const CirclePath& circle, double offset, double lag) {
  const double u = rng.uniform(0.02, 0.98);
  const Vec2 radial = (circle.evaluate(u).position - circle.centre()) / circle.radius();
  const Vec2 p = circle.centre() + (circle.radius() + rng.uniform(-offset, offset)) * radial;
  return {p, u + rng.uniform(-lag, lag) / (2 * kPi * circle.radius())};
}

double exact_on_circle(const CirclePath& c, const Vec2& p) {
  return std::abs((p - c.centre()).norm() - c.radius());
}

TEST(ContourError, PathFrameOnCirclesIsEqsFiveAndSix) {
  for (const double sweep : {2 * kPi, -2 * kPi}) {  // counter-clockwise and clockwise
    const CirclePath circle(Vec2(3, -2), 7.0, 0.0, sweep);
    for (const double u : {0.1, 0.45, 0.8}) {
      const PathPoint p = circle.evaluate(u);
      const PathFrame f = path_frame(p);
      EXPECT_NEAR(f.curvature, 1.0 / 7.0, 1e-12);
      EXPECT_LT((f.normal - (circle.centre() - p.position) / 7.0).norm(), 1e-12);
      EXPECT_NEAR(f.tangent.dot(f.normal), 0.0, 1e-15);
    }
  }
}

TEST(ContourError, ExactProjectionOnCircles) {
  Rng rng(11);
  for (const double r : {2.0, 10.0, 50.0}) {
    const CirclePath circle(Vec2(3, -2), r, 0.0, 2 * kPi);
    for (int i = 0; i < 200; ++i) {
      const Sample s = near_circle(rng, circle, 0.4, 1.0);
      const Projection p = project_to_path(circle, s.actual, s.u_ref);
      EXPECT_NEAR(p.distance, exact_on_circle(circle, s.actual), 1e-10) << "r " << r << " i " << i;
    }
  }
}

TEST(ContourError, ProjectionStaysOnTheReferenceBranch) {
  // A hairpin: the outgoing and returning legs run ~2 mm apart near x = 20.
  const CubicBezierPath hairpin({Vec2(0, 0), Vec2(100, 0), Vec2(100, 2), Vec2(0, 2)});
  const Vec2 p(20, 1.3);  // 1.27 mm above the outgoing leg, 0.67 mm below the return
  // The local minimum on the outgoing leg (u < 0.5) by dense sampling.
  double lower = INFINITY, upper = INFINITY;
  for (int k = 0; k <= 200000; ++k) {
    const double u = k / 200000.0;
    const double d = (hairpin.evaluate(u).position - p).norm();
    (u < 0.5 ? lower : upper) = std::min(u < 0.5 ? lower : upper, d);
  }
  ASSERT_LT(upper, lower);  // the far branch is closer in absolute terms
  // Sampling at du = 5e-6 (1.5 um of arc) overestimates a minimum by < 1e-5 mm.
  const Projection from_outgoing = project_to_path(hairpin, p, 0.07);
  EXPECT_LT(from_outgoing.u, 0.5);
  EXPECT_LE(from_outgoing.distance, lower + 1e-12);
  EXPECT_NEAR(from_outgoing.distance, lower, 1e-5);
  const Projection from_return = project_to_path(hairpin, p, 0.93);
  EXPECT_LE(from_return.distance, upper + 1e-12);
  EXPECT_NEAR(from_return.distance, upper, 1e-5);
}

TEST(ContourError, ProjectionAtThePathEnds) {
  const LinePath line(Vec2(0, 0), Vec2(10, 0));
  const Projection p = project_to_path(line, Vec2(-0.3, 0.4), 0.0);  // behind the start
  EXPECT_EQ(p.u, 0.0);
  EXPECT_NEAR(p.distance, 0.5, 1e-12);
}

TEST(ContourError, EstimatesOnCircles) {
  // Taylor (Eqs. 3-6) is exact to second order: its error is bounded by
  // |e|^3 / (r^2 - |e|^2) + |e|^4 / r^3 (expansion in the header); the
  // tangent line is first order (error ~ s^2 / 2r); the osculating circle of
  // a circle is the circle.
  Rng rng(5);
  for (const double r : {5.0, 20.0, 100.0}) {
    const CirclePath circle(Vec2(-4, 1), r, 0.3, 0.3 + 2 * kPi);
    double taylor_max = 0, tangent_max = 0, osculating_max = 0;
    for (int i = 0; i < 500; ++i) {
      const Sample s = near_circle(rng, circle, 0.1, 0.2);
      const PathPoint ref = circle.evaluate(s.u_ref);
      const double exact = exact_on_circle(circle, s.actual);
      const double e = (ref.position - s.actual).norm();
      const double taylor = std::abs(taylor_contour_error(ref, s.actual));
      EXPECT_LE(std::abs(taylor - exact),
                e * e * e / (r * r - e * e) + e * e * e * e / (r * r * r) + 1e-13)
          << "r " << r << " i " << i;
      EXPECT_NEAR(osculating_circle_contour_error(ref, s.actual), exact, 1e-11);
      taylor_max = std::max(taylor_max, std::abs(taylor - exact));
      tangent_max =
          std::max(tangent_max, std::abs(tangent_line_contour_error(ref, s.actual) - exact));
      osculating_max = std::max(osculating_max,
                                std::abs(osculating_circle_contour_error(ref, s.actual) - exact));
    }
    std::printf(
        "r = %5.1f mm, |e| <= 0.22 mm: max error vs exact [um]: Taylor %.4f, tangent line "
        "%.4f, osculating circle %.1e\n",
        r, taylor_max * 1e3, tangent_max * 1e3, osculating_max * 1e3);
    EXPECT_LT(taylor_max, 0.2 * tangent_max);
  }
}

TEST(ContourError, TaylorSignAndOnTangentLine) {
  // Inside a circle of radius 10 at normal offset 0.1 and no lag: exact 0.1,
  // and eps_c = -0.1 (paper's sign). On the tangent line 0.2 mm behind R:
  // the closest-point distance sqrt(r^2 + s^2) - r ~ s^2 / 2r.
  const CirclePath circle(Vec2(0, 0), 10.0, 0.0, 2 * kPi);
  const PathPoint ref = circle.evaluate(0.0);  // R = (10, 0), t = (0, 1)
  EXPECT_NEAR(taylor_contour_error(ref, Vec2(9.9, 0.0)), -0.1, 1e-15);
  const Vec2 on_tangent(10.0, -0.2);
  EXPECT_NEAR(std::abs(taylor_contour_error(ref, on_tangent)), std::hypot(10.0, 0.2) - 10.0,
              1e-6);  // s^4 / 8r^3 = 2e-7
  EXPECT_NEAR(tangent_line_contour_error(ref, on_tangent), 0.0, 1e-15);
}

TEST(ContourError, EstimatesOnSimulatedRuns) {
  // The simulated router on planned paths: the exact contour error never
  // exceeds the distance to the reference point (R lies on the path), and
  // the second-order Taylor estimate beats the tangent line.
  for (const char* name : {"circle", "epitrochoid"}) {
    const testing::PlannedPath& planned = testing::planned_path(name);
    const ReferenceTrajectory ref = interpolate(*planned.path, planned.profile, 1e-3);
    const MachineResponse run = simulate_machine(MachineOptions{}, ref, 3);
    const ContourErrorComparison c = compare_contour_estimates(*planned.path, ref, run.actual);
    double exact_max = 0.0;
    for (Eigen::Index k = 0; k < ref.samples(); ++k) {
      const double to_reference = (ref.position.row(k) - run.actual.row(k)).norm();
      EXPECT_LE(c.exact[k], to_reference + 1e-12) << name << " sample " << k;
      exact_max = std::max(exact_max, c.exact[k]);
    }
    std::printf(
        "%-12s exact max %.2f um; |estimate - exact| mean/max [um]: Taylor %.4f/%.4f, "
        "tangent %.4f/%.4f, osculating %.4f/%.4f\n",
        name, exact_max * 1e3, c.taylor.mean * 1e3, c.taylor.max * 1e3, c.tangent_line.mean * 1e3,
        c.tangent_line.max * 1e3, c.osculating_circle.mean * 1e3, c.osculating_circle.max * 1e3);
    EXPECT_LT(c.taylor.mean, c.tangent_line.mean) << name;
    EXPECT_LT(c.taylor.max, c.tangent_line.max) << name;
  }
}

}  // namespace
}  // namespace cnclab
