#include "cnclab/geometry/nurbs_surface.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/geometry/bspline_basis.hpp"

namespace cnclab {

void NurbsSurface::validate() const {
  if (points.size() != count_u * count_v) {
    throw OptionError("surface control_points", std::to_string(points.size()) + " points",
                      "expected count_u x count_v = " + std::to_string(count_u) + " x " +
                          std::to_string(count_v));
  }
  validate_knot_vector(knots_u, degree_u, count_u, "surface u");
  validate_knot_vector(knots_v, degree_v, count_v, "surface v");
  validate_control_net(points, weights, "surface");
}

namespace {

// Homogeneous derivatives A_kl = d^(k+l)/du^k dv^l sum N_i N_j w_ij P_ij and
// w_kl likewise, for k + l <= order (A3.6 with weights).
struct Homogeneous {
  Eigen::Vector3d a[3][3];
  double w[3][3];
};

Homogeneous homogeneous_derivatives(const NurbsSurface& s, double u, double v, int order) {
  const int p = s.degree_u, q = s.degree_v;
  const double uc = std::clamp(u, s.knots_u.front(), s.knots_u.back());
  const double vc = std::clamp(v, s.knots_v.front(), s.knots_v.back());
  const int su = find_span(s.knots_u, p, uc), sv = find_span(s.knots_v, q, vc);
  BasisDerivatives nu, nv;
  basis_derivatives(s.knots_u, p, su, uc, order, nu);
  basis_derivatives(s.knots_v, q, sv, vc, order, nv);
  Homogeneous h;
  for (int k = 0; k <= order; ++k) {
    for (int l = 0; k + l <= order; ++l) {
      h.a[k][l].setZero();
      h.w[k][l] = 0.0;
    }
  }
  for (int r = 0; r <= p; ++r) {
    const auto i = static_cast<std::size_t>(su - p + r);
    for (int c = 0; c <= q; ++c) {
      const auto j = static_cast<std::size_t>(sv - q + c);
      const double w = s.weight(i, j);
      const Eigen::Vector3d wp = w * s.point(i, j);
      for (int k = 0; k <= order; ++k) {
        for (int l = 0; k + l <= order; ++l) {
          const double b = nu[k][r] * nv[l][c];
          h.a[k][l] += b * wp;
          h.w[k][l] += b * w;
        }
      }
    }
  }
  return h;
}

}  // namespace

SurfaceDerivatives surface_derivatives(const NurbsSurface& s, double u, double v) {
  const Homogeneous h = homogeneous_derivatives(s, u, v, 2);
  const double w = h.w[0][0];
  SurfaceDerivatives d;
  d.point = h.a[0][0] / w;
  d.du = (h.a[1][0] - h.w[1][0] * d.point) / w;
  d.dv = (h.a[0][1] - h.w[0][1] * d.point) / w;
  d.duu = (h.a[2][0] - 2.0 * h.w[1][0] * d.du - h.w[2][0] * d.point) / w;
  d.dvv = (h.a[0][2] - 2.0 * h.w[0][1] * d.dv - h.w[0][2] * d.point) / w;
  d.duv = (h.a[1][1] - h.w[1][1] * d.point - h.w[1][0] * d.dv - h.w[0][1] * d.du) / w;
  return d;
}

Eigen::Vector3d surface_point(const NurbsSurface& s, double u, double v) {
  const Homogeneous h = homogeneous_derivatives(s, u, v, 0);
  return h.a[0][0] / h.w[0][0];
}

namespace {

// Q_a = sum_b N_b(t) w_ab P_ab / W_a, W_a = sum_b N_b(t) w_ab: the surface at
// fixed t in the direction `across` (v for an iso-u curve), as a curve along
// the other direction. `at(a, b)` gives the control index of row a, column b.
template <class Index>
NurbsCurve iso_curve(const NurbsSurface& s, int degree_along,
                     const std::vector<double>& knots_along, std::size_t count_along,
                     int degree_across, const std::vector<double>& knots_across, double t,
                     Index at) {
  const double tc = std::clamp(t, knots_across.front(), knots_across.back());
  const int span = find_span(knots_across, degree_across, tc);
  BasisDerivatives n;
  basis_derivatives(knots_across, degree_across, span, tc, 0, n);
  NurbsCurve c;
  c.degree = degree_along;
  c.knots = knots_along;
  c.points.resize(count_along);
  c.weights.resize(count_along);
  for (std::size_t a = 0; a < count_along; ++a) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    double w = 0.0;
    for (int k = 0; k <= degree_across; ++k) {
      const std::size_t index = at(a, static_cast<std::size_t>(span - degree_across + k));
      const double nw = n[0][k] * s.weights[index];
      sum += nw * s.points[index];
      w += nw;
    }
    c.points[a] = sum / w;
    c.weights[a] = w;
  }
  return c;
}

}  // namespace

NurbsCurve iso_curve_u(const NurbsSurface& s, double v) {
  return iso_curve(s, s.degree_u, s.knots_u, s.count_u, s.degree_v, s.knots_v, v,
                   [&](std::size_t i, std::size_t j) { return i * s.count_v + j; });
}

NurbsCurve iso_curve_v(const NurbsSurface& s, double u) {
  return iso_curve(s, s.degree_v, s.knots_v, s.count_v, s.degree_u, s.knots_u, u,
                   [&](std::size_t j, std::size_t i) { return i * s.count_v + j; });
}

BoundingBox sampled_bounding_box(const NurbsSurface& s, int samples) {
  samples = std::max(samples, 2);  // the grid includes both boundaries
  BoundingBox box{Eigen::Vector3d::Constant(INFINITY), Eigen::Vector3d::Constant(-INFINITY)};
  const double u0 = s.knots_u.front(), u1 = s.knots_u.back();
  const double v0 = s.knots_v.front(), v1 = s.knots_v.back();
  for (int a = 0; a < samples; ++a) {
    const NurbsCurve c = iso_curve_u(s, v0 + (v1 - v0) * a / (samples - 1));
    for (int b = 0; b < samples; ++b) {
      const Eigen::Vector3d p = curve_point(c, u0 + (u1 - u0) * b / (samples - 1));
      box.min = box.min.cwiseMin(p);
      box.max = box.max.cwiseMax(p);
    }
  }
  return box;
}

}  // namespace cnclab
