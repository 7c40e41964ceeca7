#pragma once
// Rational B-spline (NURBS) curves of any degree on clamped knot vectors:
// C(u) = sum_i N_{i,p}(u) w_i P_i / sum_i N_{i,p}(u) w_i (The NURBS Book, Eq. 4.1).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace cnclab {

struct NurbsCurve {
  int degree = 3;                       // p >= 1
  std::vector<double> knots;            // clamped, non-decreasing, points + p + 1 values
  std::vector<Eigen::Vector3d> points;  // control points P_i [mm]
  std::vector<double> weights;          // w_i > 0, one per control point (all 1: B-spline)

  // Throws OptionError naming the rule (sizes, knots, finite points,
  // weights > 0).
  void validate() const;
  double first() const { return knots.front(); }  // parameter range start
  double last() const { return knots.back(); }    // parameter range end
};

// Throws OptionError unless there is one finite weight > 0 per control point
// and every coordinate is finite; `what` prefixes the field ("surface").
void validate_control_net(const std::vector<Eigen::Vector3d>& points,
                          const std::vector<double>& weights, const std::string& what);

// Point and derivatives with respect to u at one parameter.
struct CurveDerivatives {
  Eigen::Vector3d point, d1, d2;  // C, C', C''
};

// Point only (A4.1). u outside [first, last] is clamped.
Eigen::Vector3d curve_point(const NurbsCurve& curve, double u);
// A3.2 on the homogeneous curve, then the rational quotient rule (A4.2):
// C' = (A' - w' C) / w,  C'' = (A'' - 2 w' C' - w'' C) / w.
CurveDerivatives curve_derivatives(const NurbsCurve& curve, double u);

}  // namespace cnclab
