#pragma once
// Exact rational quadratic NURBS of analytic shapes (The NURBS Book,
// Sections 7.3 and 8.5): arcs, full circles, cylinder and sphere patches.
#include <cmath>
#include <numbers>

#include "cnclab/geometry/nurbs_surface.hpp"

namespace cnclab::testing {

inline constexpr double kDeg = std::numbers::pi / 180.0;  // one degree in radians
inline constexpr double kClosedFormTol = 1e-9;            // mm: a closed form against the code

// The angle of p in the x-z plane, from +x towards +z.
inline double angle_xz(const Eigen::Vector3d& p) {
  return std::atan2(p.z(), p.x());
}

// A circular arc of radius rho about the origin in the plane spanned by the
// unit vectors e1, e2, from angle a0 to a1 (a1 - a0 < pi): degree 2, 3
// control points, middle weight cos((a1 - a0)/2).
inline NurbsCurve arc(double rho, double a0, double a1, const Eigen::Vector3d& e1,
                      const Eigen::Vector3d& e2) {
  const double half = 0.5 * (a1 - a0), mid = 0.5 * (a0 + a1);
  NurbsCurve c;
  c.degree = 2;
  c.knots = {0, 0, 0, 1, 1, 1};
  c.points = {rho * (std::cos(a0) * e1 + std::sin(a0) * e2),
              rho / std::cos(half) * (std::cos(mid) * e1 + std::sin(mid) * e2),
              rho * (std::cos(a1) * e1 + std::sin(a1) * e2)};
  c.weights = {1.0, std::cos(half), 1.0};
  return c;
}

// The full circle of radius rho in the x-y plane from 9 control points on a
// square (NURBS Book Fig. 7.16 / Ex. 7.2).
inline NurbsCurve full_circle(double rho) {
  const double r2 = std::sqrt(0.5);
  NurbsCurve c;
  c.degree = 2;
  c.knots = {0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1};
  const double xy[9][2] = {{1, 0},   {1, 1},  {0, 1},  {-1, 1}, {-1, 0},
                           {-1, -1}, {0, -1}, {1, -1}, {1, 0}};
  for (int i = 0; i < 9; ++i) {
    c.points.emplace_back(rho * xy[i][0], rho * xy[i][1], 0.0);
    c.weights.push_back(i % 2 ? r2 : 1.0);
  }
  return c;
}

// Cylinder of radius rho about the y axis: u runs along the cross-section
// arc in the x-z plane from angle a0 to a1 (x = rho cos a, z = rho sin a),
// v along y in [0, length] (degree 1).
inline NurbsSurface cylinder(double rho, double a0, double a1, double length) {
  const NurbsCurve c = arc(rho, a0, a1, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  NurbsSurface s;
  s.degree_u = 2;
  s.degree_v = 1;
  s.knots_u = c.knots;
  s.knots_v = {0, 0, 1, 1};
  s.count_u = 3;
  s.count_v = 2;
  for (std::size_t i = 0; i < 3; ++i) {
    for (double y : {0.0, length}) {
      s.points.push_back(c.points[i] + Eigen::Vector3d(0, y, 0));
      s.weights.push_back(c.weights[i]);
    }
  }
  return s;
}

// Sphere patch of radius rho about the origin: u along a meridian from
// latitude -lat to +lat, v along longitude 0..90 degrees (surface of
// revolution: P_ij = (r_i X_j, r_i Y_j, z_i), w_ij = w_i w_j).
inline NurbsSurface sphere_patch(double rho, double lat) {
  const NurbsCurve meridian =
      arc(rho, -lat, lat, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  const NurbsCurve quarter =
      arc(1.0, 0.0, std::numbers::pi / 2, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  NurbsSurface s;
  s.degree_u = s.degree_v = 2;
  s.knots_u = s.knots_v = {0, 0, 0, 1, 1, 1};
  s.count_u = s.count_v = 3;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      const double r = meridian.points[i].x(), z = meridian.points[i].z();
      s.points.emplace_back(r * quarter.points[j].x(), r * quarter.points[j].y(), z);
      s.weights.push_back(meridian.weights[i] * quarter.weights[j]);
    }
  }
  return s;
}

}  // namespace cnclab::testing
