#include "cnclab/geometry/surface_curvature.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace cnclab {

SurfaceCurvatures surface_curvatures(const SurfaceDerivatives& d, const Eigen::Vector3d& n,
                                     const Eigen::Vector3d& along) {
  const double e = d.du.dot(d.du), f = d.du.dot(d.dv), g = d.dv.dot(d.dv);
  const double l = d.duu.dot(n), m = d.duv.dot(n), nn = d.dvv.dot(n);
  const double det = e * g - f * f;
  // Normal curvature along a tangent vector w: its coordinates (a, b) in
  // (S_u, S_v) solve I [a b]^T = [w.S_u w.S_v]^T.
  const auto normal_curvature = [&](const Eigen::Vector3d& w) {
    const double wu = w.dot(d.du), wv = w.dot(d.dv);
    const double a = (g * wu - f * wv) / det, b = (e * wv - f * wu) / det;
    return (l * a * a + 2 * m * a * b + nn * b * b) / (e * a * a + 2 * f * a * b + g * b * b);
  };
  SurfaceCurvatures c;
  c.along = normal_curvature(along);
  c.across = normal_curvature(n.cross(along));
  const double h = (e * nn - 2 * f * m + g * l) / (2 * det);
  const double k = (l * nn - m * m) / det;
  const double root = std::sqrt(std::max(0.0, h * h - k));  // >= 0 but for rounding
  c.max = h + root;
  c.min = h - root;
  return c;
}

}  // namespace cnclab
