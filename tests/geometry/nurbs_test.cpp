#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/geometry/nurbs_curve.hpp"
#include "cnclab/geometry/nurbs_surface.hpp"
#include "common/expect_error.hpp"
#include "geometry/shapes.hpp"

namespace cnclab {
namespace {

using testing::arc;
using testing::cylinder;
using testing::full_circle;
using testing::sphere_patch;

constexpr double kShapeTol = 1e-12;  // mm, rational quadratics are exact
constexpr double kPi = std::numbers::pi;

TEST(NurbsCurve, FullCircleIsExact) {
  const double rho = 37.5;
  const NurbsCurve c = full_circle(rho);
  c.validate();
  for (int k = 0; k <= 1000; ++k) {
    const double u = k / 1000.0;
    const CurveDerivatives d = curve_derivatives(c, u);
    EXPECT_NEAR(d.point.norm(), rho, kShapeTol) << u;
    EXPECT_NEAR(d.point.z(), 0.0, kShapeTol);
    // Tangent perpendicular to the radius (except where the derivative is
    // one-sided at a double knot, still perpendicular).
    EXPECT_NEAR(d.d1.dot(d.point) / (d.d1.norm() * rho), 0.0, 1e-12) << u;
  }
}

TEST(NurbsSurface, CylinderPatchIsExact) {
  const double rho = 12.0;
  const NurbsSurface s = cylinder(rho, 0.2, 2.9, 30.0);
  s.validate();
  Rng rng(3);
  for (int k = 0; k < 2000; ++k) {
    const double u = rng.uniform(), v = rng.uniform();
    const SurfaceDerivatives d = surface_derivatives(s, u, v);
    EXPECT_NEAR(std::hypot(d.point.x(), d.point.z()), rho, kShapeTol);
    EXPECT_NEAR(d.point.y(), 30.0 * v, kShapeTol);
    // S_u x S_v points into the cylinder (u runs counter-clockwise in x-z, v along +y).
    const Eigen::Vector3d n = d.du.cross(d.dv).normalized();
    const Eigen::Vector3d radial = Eigen::Vector3d(d.point.x(), 0, d.point.z()) / rho;
    EXPECT_NEAR((n + radial).norm(), 0.0, 1e-12);
  }
}

TEST(NurbsSurface, SpherePatchIsExact) {
  const double rho = 25.0;
  const NurbsSurface s = sphere_patch(rho, 40.0 * kPi / 180.0);
  s.validate();
  Rng rng(4);
  for (int k = 0; k < 2000; ++k) {
    const SurfaceDerivatives d = surface_derivatives(s, rng.uniform(), rng.uniform());
    EXPECT_NEAR(d.point.norm(), rho, kShapeTol);
    const Eigen::Vector3d n = d.du.cross(d.dv).normalized();
    EXPECT_NEAR(std::abs(n.dot(d.point / rho)), 1.0, 1e-12);
  }
  // Corners interpolate the clamped control net.
  EXPECT_NEAR((surface_point(s, 0, 0) - s.point(0, 0)).norm(), 0.0, kShapeTol);
  EXPECT_NEAR((surface_point(s, 1, 1) - s.point(2, 2)).norm(), 0.0, kShapeTol);
}

double binomial(int n, int k) {
  double b = 1;
  for (int i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}
double bernstein(int n, int i, double u) {
  return binomial(n, i) * std::pow(u, i) * std::pow(1 - u, n - i);
}

// One knot span: the B-spline is its Bezier curve, sum B_i,p P_i, with
// C' = p sum B_i,p-1 (P_i+1 - P_i) and C'' = p(p-1) sum B_i,p-2 (P_i+2 - 2P_i+1 + P_i);
// rational: sum B w P / sum B w.
TEST(NurbsCurve, OneSpanEqualsBezierForm) {
  Rng rng(5);
  for (int p = 1; p <= 7; ++p) {
    NurbsCurve c;
    c.degree = p;
    c.knots.assign(static_cast<std::size_t>(p + 1), 0.0);
    c.knots.insert(c.knots.end(), static_cast<std::size_t>(p + 1), 1.0);
    for (int i = 0; i <= p; ++i) {
      c.points.emplace_back(rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50));
    }
    c.weights.assign(c.points.size(), 1.0);
    c.validate();
    for (double u : {0.0, 0.13, 0.5, 0.77, 1.0}) {
      Eigen::Vector3d b = Eigen::Vector3d::Zero(), b1 = b, b2 = b;
      for (int i = 0; i <= p; ++i) b += bernstein(p, i, u) * c.points[i];
      for (int i = 0; i < p; ++i)
        b1 += p * bernstein(p - 1, i, u) * (c.points[i + 1] - c.points[i]);
      for (int i = 0; i + 1 < p; ++i) {
        b2 += p * (p - 1) * bernstein(p - 2, i, u) *
              (c.points[i + 2] - 2 * c.points[i + 1] + c.points[i]);
      }
      const CurveDerivatives d = curve_derivatives(c, u);
      EXPECT_NEAR((d.point - b).norm(), 0.0, 1e-11) << p << " " << u;
      EXPECT_NEAR((d.d1 - b1).norm(), 0.0, 1e-10) << p << " " << u;
      EXPECT_NEAR((d.d2 - b2).norm(), 0.0, 1e-8) << p << " " << u;
    }
    for (auto& w : c.weights) w = rng.uniform(0.3, 3.0);
    for (double u : {0.0, 0.31, 0.9, 1.0}) {
      Eigen::Vector3d a = Eigen::Vector3d::Zero();
      double w = 0;
      for (int i = 0; i <= p; ++i) {
        a += bernstein(p, i, u) * c.weights[i] * c.points[i];
        w += bernstein(p, i, u) * c.weights[i];
      }
      EXPECT_NEAR((curve_point(c, u) - a / w).norm(), 0.0, 1e-11) << p << " " << u;
    }
  }
}

// A rational surface with non-uniform knots, an interior double knot and
// random weights; points away from knots (where derivatives are smooth).
NurbsSurface random_surface(Rng& rng) {
  NurbsSurface s;
  s.degree_u = 3;
  s.degree_v = 2;
  s.knots_u = {0, 0, 0, 0, 0.4, 0.4, 1, 1, 1, 1};
  s.knots_v = {0, 0, 0, 0.3, 0.6, 1, 1, 1};
  s.count_u = 6;
  s.count_v = 5;
  for (std::size_t i = 0; i < s.count_u * s.count_v; ++i) {
    s.points.emplace_back(rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-20, 20));
    s.weights.push_back(rng.uniform(0.5, 2.0));
  }
  s.validate();
  return s;
}

bool near_knot(double t, const std::vector<double>& knots) {
  for (double k : knots) {
    if (std::abs(t - k) < 1e-3) return true;
  }
  return false;
}

TEST(NurbsSurface, DerivativesMatchCentralDifferences) {
  Rng rng(6);
  const NurbsSurface s = random_surface(rng);
  const double h = 1e-5;
  int checked = 0;
  while (checked < 300) {
    const double u = rng.uniform(0.01, 0.99), v = rng.uniform(0.01, 0.99);
    if (near_knot(u, s.knots_u) || near_knot(v, s.knots_v)) continue;
    ++checked;
    const SurfaceDerivatives d = surface_derivatives(s, u, v);
    const SurfaceDerivatives up = surface_derivatives(s, u + h, v);
    const SurfaceDerivatives um = surface_derivatives(s, u - h, v);
    const SurfaceDerivatives vp = surface_derivatives(s, u, v + h);
    const SurfaceDerivatives vm = surface_derivatives(s, u, v - h);
    const double scale = 1.0 + d.du.norm() + d.dv.norm() + d.duu.norm() + d.dvv.norm();
    const double tol = 1e-6 * scale;
    EXPECT_NEAR((d.du - (up.point - um.point) / (2 * h)).norm(), 0.0, tol);
    EXPECT_NEAR((d.dv - (vp.point - vm.point) / (2 * h)).norm(), 0.0, tol);
    EXPECT_NEAR((d.duu - (up.du - um.du) / (2 * h)).norm(), 0.0, tol);
    EXPECT_NEAR((d.dvv - (vp.dv - vm.dv) / (2 * h)).norm(), 0.0, tol);
    EXPECT_NEAR((d.duv - (vp.du - vm.du) / (2 * h)).norm(), 0.0, tol);
    EXPECT_NEAR((d.duv - (up.dv - um.dv) / (2 * h)).norm(), 0.0, tol);
    EXPECT_NEAR((surface_point(s, u, v) - d.point).norm(), 0.0, 1e-12);
  }
}

TEST(NurbsSurface, IsoCurveIsTheSurfaceAtConstantV) {
  Rng rng(8);
  const NurbsSurface s = random_surface(rng);
  for (double v : {0.0, 0.3, 0.45, 1.0}) {
    const NurbsCurve c = iso_curve_u(s, v);
    c.validate();
    for (int k = 0; k <= 50; ++k) {
      const double u = k / 50.0;
      if (near_knot(u, s.knots_u)) continue;
      const CurveDerivatives cd = curve_derivatives(c, u);
      const SurfaceDerivatives sd = surface_derivatives(s, u, v);
      EXPECT_NEAR((cd.point - sd.point).norm(), 0.0, 1e-11);
      EXPECT_NEAR((cd.d1 - sd.du).norm(), 0.0, 1e-9);
      EXPECT_NEAR((cd.d2 - sd.duu).norm(), 0.0, 1e-7);
    }
  }
}

TEST(NurbsSurface, IsoCurveVIsTheSurfaceAtConstantU) {
  Rng rng(9);
  const NurbsSurface s = random_surface(rng);
  for (double u : {0.0, 0.3, 0.45, 1.0}) {
    const NurbsCurve c = iso_curve_v(s, u);
    c.validate();
    for (int k = 0; k <= 50; ++k) {
      const double v = k / 50.0;
      if (near_knot(v, s.knots_v)) continue;
      const CurveDerivatives cd = curve_derivatives(c, v);
      const SurfaceDerivatives sd = surface_derivatives(s, u, v);
      EXPECT_NEAR((cd.point - sd.point).norm(), 0.0, 1e-11);
      EXPECT_NEAR((cd.d1 - sd.dv).norm(), 0.0, 1e-9);
      EXPECT_NEAR((cd.d2 - sd.dvv).norm(), 0.0, 1e-7);
    }
  }
}

TEST(NurbsCurve, DerivativesMatchCentralDifferences) {
  const NurbsCurve c = arc(10.0, 0.3, 2.5, Eigen::Vector3d::UnitX(), Eigen::Vector3d(0, 0.6, 0.8));
  const double h = 1e-5;
  for (double u = 0.05; u < 0.96; u += 0.1) {
    const CurveDerivatives d = curve_derivatives(c, u), p = curve_derivatives(c, u + h),
                           m = curve_derivatives(c, u - h);
    EXPECT_NEAR((d.d1 - (p.point - m.point) / (2 * h)).norm(), 0.0, 1e-5);
    EXPECT_NEAR((d.d2 - (p.d1 - m.d1) / (2 * h)).norm(), 0.0, 1e-4);
    EXPECT_NEAR((d.d3 - (p.d2 - m.d2) / (2 * h)).norm(), 0.0, 1e-4 * (1 + d.d3.norm()));
  }
}

// C''' against central differences of C'' on rational curves of degrees
// 1..6 with random weights and non-uniform knots, away from the knots (where
// C''' of a degree <= 3 curve jumps). Degree <= 2 B-spline pieces have no
// third derivative; the rational ones do.
TEST(NurbsCurve, ThirdDerivativeMatchesCentralDifferences) {
  Rng rng(11);
  for (int p = 1; p <= 6; ++p) {
    NurbsCurve c;
    c.degree = p;
    const int count = p + 4;
    c.knots.assign(static_cast<std::size_t>(p + 1), 0.0);
    double t = 0.0;
    for (int i = 0; i < count - p - 1; ++i) c.knots.push_back(t += rng.uniform(0.3, 1.0));
    t += rng.uniform(0.3, 1.0);
    for (int i = 0; i <= p; ++i) c.knots.push_back(t);
    for (int i = 0; i < count; ++i) {
      c.points.emplace_back(rng.uniform(-20, 20), rng.uniform(-20, 20), rng.uniform(-20, 20));
      c.weights.push_back(rng.uniform(0.5, 2.0));
    }
    c.validate();
    const double h = 1e-5;
    int checked = 0;
    while (checked < 40) {
      const double u = rng.uniform(c.first() + 1e-3, c.last() - 1e-3);
      if (near_knot(u, c.knots)) continue;
      ++checked;
      const CurveDerivatives d = curve_derivatives(c, u), plus = curve_derivatives(c, u + h),
                             minus = curve_derivatives(c, u - h);
      const Eigen::Vector3d fd = (plus.d2 - minus.d2) / (2 * h);
      EXPECT_NEAR((d.d3 - fd).norm(), 0.0, 1e-5 * (1 + d.d3.norm())) << p << " " << u;
    }
  }
  // A polynomial cubic Bezier: C''' = 6 (P3 - 3 P2 + 3 P1 - P0) exactly.
  NurbsCurve bezier;
  bezier.degree = 3;
  bezier.knots = {0, 0, 0, 0, 1, 1, 1, 1};
  bezier.points = {{0, 0, 0}, {1, 3, 0}, {4, -2, 1}, {6, 1, 0}};
  bezier.weights = {1, 1, 1, 1};
  const Eigen::Vector3d expected =
      6.0 * (bezier.points[3] - 3.0 * bezier.points[2] + 3.0 * bezier.points[1] - bezier.points[0]);
  for (double u : {0.0, 0.4, 1.0}) {
    EXPECT_NEAR((curve_derivatives(bezier, u).d3 - expected).norm(), 0.0, 1e-12) << u;
  }
}

std::string validation_message(const NurbsSurface& s) {
  return testing::error_message<OptionError>([&] { s.validate(); });
}

TEST(NurbsSurface, ValidationNamesTheProblem) {
  Rng rng(9);
  const NurbsSurface good = random_surface(rng);
  NurbsSurface s = good;
  s.weights[7] = 0.0;
  EXPECT_NE(validation_message(s).find("surface weights = [7] = 0: weights must be finite and > 0"),
            std::string::npos)
      << validation_message(s);
  s = good;
  s.weights[2] = -1.0;
  EXPECT_NE(validation_message(s).find("> 0"), std::string::npos);
  s = good;
  s.points.pop_back();
  EXPECT_NE(validation_message(s).find("expected count_u x count_v = 6 x 5"), std::string::npos);
  s = good;
  s.knots_v[3] = 0.9;  // 0.9 > 0.6 next
  EXPECT_NE(validation_message(s).find("surface v knots"), std::string::npos);
  EXPECT_NE(validation_message(s).find("non-decreasing"), std::string::npos);
  s = good;
  s.weights.pop_back();
  EXPECT_NE(validation_message(s).find("need one weight per control point (30)"),
            std::string::npos);
  s = good;
  s.points[4].x() = INFINITY;
  EXPECT_NE(validation_message(s).find("finite"), std::string::npos);
  EXPECT_EQ(validation_message(good), "no error");
}

}  // namespace
}  // namespace cnclab
