#include "cnclab/geometry/nurbs_curve.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/geometry/bspline_basis.hpp"

namespace cnclab {

void NurbsCurve::validate() const {
  validate_knot_vector(knots, degree, points.size(), "curve");
  validate_control_net(points, weights, "curve");
}

void validate_control_net(const std::vector<Eigen::Vector3d>& points,
                          const std::vector<double>& weights, const std::string& what) {
  if (weights.size() != points.size()) {
    throw OptionError(what + " weights", std::to_string(weights.size()) + " values",
                      "need one weight per control point (" + std::to_string(points.size()) + ")");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!points[i].allFinite()) {
      throw OptionError(what + " control point", "[" + std::to_string(i) + "]",
                        "coordinates must be finite");
    }
    if (!(weights[i] > 0.0) || !std::isfinite(weights[i])) {
      throw OptionError(what + " weights",
                        "[" + std::to_string(i) + "] = " + shortest_double(weights[i]),
                        "weights must be finite and > 0");
    }
  }
}

Eigen::Vector3d curve_point(const NurbsCurve& c, double u) {
  const int span = find_span(c.knots, c.degree, u);
  BasisDerivatives n;
  basis_derivatives(c.knots, c.degree, span, std::clamp(u, c.first(), c.last()), 0, n);
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  double w = 0.0;
  for (int j = 0; j <= c.degree; ++j) {
    const auto i = static_cast<std::size_t>(span - c.degree + j);
    const double nw = n[0][j] * c.weights[i];
    a += nw * c.points[i];
    w += nw;
  }
  return a / w;
}

CurveDerivatives curve_derivatives(const NurbsCurve& c, double u) {
  const int span = find_span(c.knots, c.degree, u);
  BasisDerivatives n;
  basis_derivatives(c.knots, c.degree, span, std::clamp(u, c.first(), c.last()), 2, n);
  Eigen::Vector3d a[3] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(),
                          Eigen::Vector3d::Zero()};
  double w[3] = {0.0, 0.0, 0.0};
  for (int j = 0; j <= c.degree; ++j) {
    const auto i = static_cast<std::size_t>(span - c.degree + j);
    for (int k = 0; k <= 2; ++k) {
      const double nw = n[k][j] * c.weights[i];
      a[k] += nw * c.points[i];
      w[k] += nw;
    }
  }
  CurveDerivatives d;
  d.point = a[0] / w[0];
  d.d1 = (a[1] - w[1] * d.point) / w[0];
  d.d2 = (a[2] - 2.0 * w[1] * d.d1 - w[2] * d.point) / w[0];
  return d;
}

}  // namespace cnclab
