#pragma once
// Rational B-spline (NURBS) surfaces of any degree on clamped knot vectors:
// S(u,v) = sum_ij N_i,p(u) N_j,q(v) w_ij P_ij / sum_ij N_i,p(u) N_j,q(v) w_ij
// (The NURBS Book, Eq. 4.15).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "cnclab/geometry/nurbs_curve.hpp"

namespace cnclab {

struct NurbsSurface {
  int degree_u = 3, degree_v = 3;       // p, q >= 1
  std::vector<double> knots_u;          // clamped, count_u + degree_u + 1 values
  std::vector<double> knots_v;          // clamped, count_v + degree_v + 1 values
  std::size_t count_u = 0;              // control points along u
  std::size_t count_v = 0;              // control points along v
  std::vector<Eigen::Vector3d> points;  // P_ij at [i * count_v + j] (i along u) [mm]
  std::vector<double> weights;          // w_ij > 0, same layout

  // Throws OptionError naming the rule (sizes, knots, weights > 0, finite).
  void validate() const;
  const Eigen::Vector3d& point(std::size_t i, std::size_t j) const {
    return points[i * count_v + j];
  }
  double weight(std::size_t i, std::size_t j) const { return weights[i * count_v + j]; }
};

// Point, first and second partial derivatives at (u, v).
struct SurfaceDerivatives {
  Eigen::Vector3d point, du, dv, duu, duv, dvv;
};

// A3.6 on the homogeneous surface, then the rational quotient rule (A4.4):
// S_u = (A_u - w_u S)/w, S_uu = (A_uu - 2 w_u S_u - w_uu S)/w,
// S_uv = (A_uv - w_uv S - w_u S_v - w_v S_u)/w (and likewise in v).
// (u, v) outside the parameter rectangle are clamped.
SurfaceDerivatives surface_derivatives(const NurbsSurface& surface, double u, double v);
Eigen::Vector3d surface_point(const NurbsSurface& surface, double u, double v);

// The iso-parametric curve u -> S(u, v) at fixed v as an exact NURBS curve:
// Q_i = sum_j N_j,q(v) w_ij P_ij / W_i with weights W_i = sum_j N_j,q(v) w_ij.
NurbsCurve iso_curve_u(const NurbsSurface& surface, double v);
// The same along v at fixed u: v -> S(u, v).
NurbsCurve iso_curve_v(const NurbsSurface& surface, double u);

// Axis-aligned bounding box of S over its parameter rectangle, from a grid of
// samples x samples points (>= 2, boundaries included; exact in x and y for the designed surfaces
// whose boundary control points span the box; accurate to the sampling in z).
struct BoundingBox {
  Eigen::Vector3d min, max;
  Eigen::Vector3d size() const { return max - min; }
};
BoundingBox sampled_bounding_box(const NurbsSurface& surface, int samples);

}  // namespace cnclab
