#pragma once
// Cubic smoothing spline equivalent to MATLAB's csaps(x, y, p, [], w): the
// natural cubic spline f minimising
//   p sum_i w_i (y_i - f(x_i))^2 + (1 - p) integral f''(x)^2 dx,
// p in [0, 1]: p = 0 gives the weighted least-squares straight line, p = 1
// the natural cubic interpolant (MATLAB documentation of csaps).
//
// The abscissa matters: p weighs a sum over samples against an integral
// over x, so the same p smooths differently in seconds and in samples. On
// uniform spacing h the spline is, away from the ends, the linear filter
//   H(w) = 1 / (1 + lambda 48 sin^4(w h / 2) / (h^3 (2 + cos w h))),
//   lambda = (1 - p) / p,   H ~ 1 / (1 + lambda h w^4) for small w h,
// (w per unit of x). Seed 002 smooths 1 ms data with p = 5e-2: with x the
// sample index (h = 1, i.e. x in ms) the half-power point is near
// w = 0.48 rad/sample = 76 Hz, which removes measurement noise as the paper
// says; with x in seconds it would be 0.4 Hz and flatten the signal itself.
// cnclab therefore applies p to the sample index.
//
// Solved by Reinsch's algorithm (Green & Silverman 1994, Sec. 2.3):
//   (R + lambda Q^T W^-1 Q) gamma = Q^T y,   g = y - lambda W^-1 Q gamma,
// g the values at the sites, gamma the second derivatives at the interior
// sites; a banded symmetric positive-definite system, O(n).
#include <Eigen/Core>

namespace cnclab {

class SmoothingSpline {
 public:
  // x strictly increasing, finite; y finite; same length >= 2; p in [0, 1];
  // weights empty (all 1) or positive with the same length. Throws
  // cnclab::Error naming the offending index/value.
  static SmoothingSpline fit(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double p,
                             const Eigen::VectorXd& weights = {});

  // f at the sites x_i.
  const Eigen::VectorXd& values() const { return values_; }
  // f'' at the sites (0 at both ends: natural spline).
  const Eigen::VectorXd& second_derivatives() const { return second_; }
  // f, f' or f'' anywhere (linear extrapolation outside [x_0, x_n-1]).
  double operator()(double x) const { return evaluate(x, 0); }
  double derivative(double x, int order) const { return evaluate(x, order); }

 private:
  double evaluate(double x, int order) const;
  Eigen::VectorXd x_, values_, second_;
};

}  // namespace cnclab
