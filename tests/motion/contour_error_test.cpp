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

// P = R + a t + b n in the frame at the reference point (b > 0 towards the
// centre of curvature).
struct LocalOffset {
  double a, b;
};
LocalOffset local_offset(const PathPoint& ref, const Vec2& actual) {
  const PathFrame f = path_frame(ref);
  const Vec2 d = actual - ref.position;
  return {d.dot(f.tangent), d.dot(f.normal)};
}

TEST(ContourError, EstimatesOnCircles) {
  // On a circle the exact distance is |sqrt(a^2 + (r - b)^2) - r|, whose
  // series in a has the Taylor estimate (Eqs. 3-6) as its first terms: the
  // error is at most a^4 / (8 |r - b|^3) (alternating series). The tangent
  // line is first order (error ~ a^2 / 2r); the osculating circle of a circle
  // is the circle.
  Rng rng(5);
  for (const double r : {5.0, 20.0, 100.0}) {
    const CirclePath circle(Vec2(-4, 1), r, 0.3, 0.3 + 2 * kPi);
    double taylor_max = 0, tangent_max = 0, osculating_max = 0;
    for (int i = 0; i < 500; ++i) {
      const Sample s = near_circle(rng, circle, 0.1, 0.2);
      const PathPoint ref = circle.evaluate(s.u_ref);
      const double exact = exact_on_circle(circle, s.actual);
      const auto [a, b] = local_offset(ref, s.actual);
      const double taylor = std::abs(taylor_contour_error(ref, s.actual));
      EXPECT_LE(std::abs(taylor - exact), std::pow(a, 4) / (8 * std::pow(r - b, 3)) + 1e-13)
          << "r " << r << " i " << i;
      EXPECT_NEAR(osculating_circle_contour_error(ref, s.actual), exact, 1e-11);
      taylor_max = std::max(taylor_max, std::abs(taylor - exact));
      tangent_max =
          std::max(tangent_max, std::abs(tangent_line_contour_error(ref, s.actual) - exact));
      osculating_max = std::max(osculating_max,
                                std::abs(osculating_circle_contour_error(ref, s.actual) - exact));
    }
    std::printf(
        "r = %5.1f mm, |e| <= 0.22 mm: max error vs exact [um]: Taylor %.6f, tangent line "
        "%.4f, osculating circle %.1e\n",
        r, taylor_max * 1e3, tangent_max * 1e3, osculating_max * 1e3);
    EXPECT_LT(taylor_max, 1e-3 * tangent_max);
  }
}

TEST(ContourError, TaylorOnACircleInsideAndOutsideIsTheClosedForm) {
  // R = (r, 0) on a counter-clockwise circle about the origin: t = (0, 1),
  // n = (-1, 0). P = R + a t + b n, inside (b > 0) and outside (b < 0),
  // leading and lagging (a of both signs). Exact: |sqrt(a^2 + (r - b)^2) - r|.
  // (1e-13 in the bound: rounding of the exact value's difference at r = 50.)
  for (const double r : {2.0, 10.0, 50.0}) {
    const CirclePath circle(Vec2(0, 0), r, 0.0, 2 * kPi);
    const PathPoint ref = circle.evaluate(0.0);
    for (const double b : {0.1, 0.02, -0.02, -0.1}) {
      for (const double a : {-0.2, -0.1, 0.05, 0.1, 0.2}) {
        const Vec2 p = ref.position + Vec2(-b, a);
        const double exact = std::abs(std::hypot(a, r - b) - r);
        const double eps = taylor_contour_error(ref, p);
        EXPECT_LT(eps, 0.0) << "the paper's sign";
        EXPECT_LE(std::abs(-eps - exact), std::pow(a, 4) / (8 * std::pow(r - b, 3)) + 1e-13)
            << "r " << r << " a " << a << " b " << b;
      }
    }
  }
  // A point 0.1 mm inside and 0.1 mm along a circle of r = 10: the
  // bound is a^4 / (8 (r - b)^3) = 1.3e-8 mm; the printed minus sign would be
  // off by kappa^2 a^2 b = 1.0e-5 mm.
  const CirclePath circle(Vec2(0, 0), 10.0, 0.0, 2 * kPi);
  const double exact = 10.0 - std::hypot(0.1, 9.9);
  EXPECT_NEAR(-taylor_contour_error(circle.evaluate(0.0), Vec2(9.9, 0.1)), exact, 1.3e-8);
}

// An ellipse (A cos th, B sin th) as the path's local data at th, and the
// exact distance from P to it by dense sampling refined by golden-section
// search (independent of project_to_path).
PathPoint ellipse_point(double A, double B, double th) {
  PathPoint p;
  p.position = Vec2(A * std::cos(th), B * std::sin(th));
  p.d1 = Vec2(-A * std::sin(th), B * std::cos(th));
  p.d2 = Vec2(-A * std::cos(th), -B * std::sin(th));
  p.d3 = -p.d1;
  return p;
}
double distance_to_ellipse(double A, double B, const Vec2& p, double th0) {
  const auto dist = [&](double th) {
    return (Vec2(A * std::cos(th), B * std::sin(th)) - p).norm();
  };
  constexpr int kSamples = 4000;  // over th0 +- 0.2 rad: the branch near R
  double best = th0, best_d = dist(th0), step = 0.4 / kSamples;
  for (int k = 0; k <= kSamples; ++k) {
    const double th = th0 - 0.2 + k * step;
    if (dist(th) < best_d) best_d = dist(th), best = th;
  }
  double lo = best - step, hi = best + step;
  const double g = (std::sqrt(5.0) - 1) / 2;
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
    (dist(x1) < dist(x2) ? hi : lo) = dist(x1) < dist(x2) ? x2 : x1;
  }
  return dist((lo + hi) / 2);
}

TEST(ContourError, TaylorOnAnEllipseIsThirdOrderAndFourthAtTheVertices) {
  // Error of |eps_c| against the exact distance for P = R + h (cos phi,
  // sin phi) over phi (inside and outside, leading and lagging), as h halves:
  // a method of order q gains 2^q. At a vertex dkappa/ds = 0 and the series
  // matches the exact one to the a^4 term (as on a circle); elsewhere the
  // change of curvature leaves an |e|^3 term. The printed minus sign of
  // Eq. 3's denominator would be third order at the vertices too.
  constexpr double A = 20.0, B = 8.0;
  const auto worst = [&](double th, double h) {
    const PathPoint ref = ellipse_point(A, B, th);
    double w = 0;
    for (int k = 0; k < 16; ++k) {
      const double phi = 2 * kPi * (k + 0.5) / 16;
      const Vec2 p = ref.position + h * Vec2(std::cos(phi), std::sin(phi));
      const double exact = distance_to_ellipse(A, B, p, th);
      w = std::max(w, std::abs(std::abs(taylor_contour_error(ref, p)) - exact));
    }
    return w;
  };
  for (const double th : {0.0, kPi / 2, 0.7, 2.0}) {
    const bool vertex = th == 0.0 || th == kPi / 2;
    const double e1 = worst(th, 0.2), e2 = worst(th, 0.1), e3 = worst(th, 0.05);
    std::printf("ellipse th %.2f: max error [um] at |e| 0.2/0.1/0.05 mm: %.2e %.2e %.2e\n", th,
                e1 * 1e3, e2 * 1e3, e3 * 1e3);
    const double gain = vertex ? 12.0 : 6.0;  // 2^4 and 2^3, with margin
    EXPECT_GT(e1 / e2, gain) << "th " << th;
    EXPECT_GT(e2 / e3, gain) << "th " << th;
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
