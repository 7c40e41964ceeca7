#pragma once
// Peak axis velocity, acceleration and jerk of a sampled reference by forward
// differences of its positions, the independent check of the planner's
// limits (docs/motion.md). With h the sample period,
//   v_k = (p_k+1 - p_k) / h,
//   a_k = (p_k+2 - 2 p_k+1 + p_k) / h^2,
//   j_k = (p_k+3 - 3 p_k+2 + 3 p_k+1 - p_k) / h^3,
// and each is a weighted average with positive weights (the B-spline of
// order 1, 2, 3 on [t_k, t_k+n]) of the true derivative: by Peano's kernel
// theorem Delta^n p_k = h^n int B_n(t) p^(n)(t) dt, B_n >= 0, int B_n = 1.
// So |difference| <= max |true derivative| over those n samples, and a
// difference above a limit proves the true derivative exceeds it too.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>

namespace cnclab::testing {

struct DifferencePeaks {
  std::array<double, 2> v{}, a{}, j{};  // per axis x, y [mm/s, mm/s^2, mm/s^3]
};

inline DifferencePeaks difference_peaks(const Eigen::MatrixX2d& p, double h) {
  DifferencePeaks peaks;
  for (Eigen::Index k = 0; k + 3 < p.rows(); ++k) {
    for (int i = 0; i < 2; ++i) {
      const double p0 = p(k, i), p1 = p(k + 1, i), p2 = p(k + 2, i), p3 = p(k + 3, i);
      peaks.v[i] = std::max(peaks.v[i], std::abs(p1 - p0) / h);
      peaks.a[i] = std::max(peaks.a[i], std::abs(p2 - 2 * p1 + p0) / (h * h));
      peaks.j[i] = std::max(peaks.j[i], std::abs(p3 - 3 * p2 + 3 * p1 - p0) / (h * h * h));
    }
  }
  return peaks;
}

}  // namespace cnclab::testing
