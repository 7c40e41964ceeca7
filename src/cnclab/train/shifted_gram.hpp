#pragma once
// Damped systems of one Gram matrix G (symmetric positive semi-definite:
// J^T J or J J^T) for many dampings, as Levenberg-Marquardt needs them:
//   solve (b G + c I) x = r   for a scale b > 0 and a shift c > 0,
//   effective_count(a, b) = sum_i b l_i / (b l_i + a) = n - a tr((b G + a I)^-1)
// (l_i the eigenvalues of G, n its size; trainbr's gamma, trainbr.hpp).
//
// Two decompositions (Method):
//  - spectral: once per G, the Householder reduction G = Q T Q^T (T
//    tridiagonal; Eigen::Tridiagonalization, 4/3 n^3 flops) and the
//    eigenvalues of T, which are G's (Eigen's tridiagonal QR, O(n^2)); then
//    every damping costs O(n^2): x = Q (b T + c I)^-1 Q^T r, with b T + c I
//    factored as L D L^T in O(n) (no pivoting: positive definite for c > 0),
//    and the count is the sum above over the eigenvalues (clamped at 0).
//  - cholesky: per damping, the Cholesky factor L of b G + c I (n^3 / 3
//    flops); count = n - a ||L^-1||_F^2 (tr(A^-1) = ||L^-1||_F^2 for
//    A = L L^T). What lm/trainbr did before the spectral method existed.
// Both are backward stable: for the same G they agree to about
// n eps cond(b G + c I), the rounding of the problem itself.
// Eigen's tridiagonal reduction is not blocked (its rank-2 updates stream
// the whole trailing matrix for every column), so above ~1,000 it costs
// more than a few Choleskys; automatic_method() says which to use.
#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>

namespace cnclab {

class ShiftedGram {
 public:
  enum class Method { spectral, cholesky };

  // Spectral up to this size, Cholesky above (measured: docs/performance.md).
  static constexpr Eigen::Index kSpectralMaxSize = 1024;
  static Method automatic_method(Eigen::Index n) {
    return n <= kSpectralMaxSize ? Method::spectral : Method::cholesky;
  }

  // Takes G (its lower triangle is read; the strict upper part may hold
  // anything) and decomposes it (spectral). False if G is not finite.
  bool reset(Eigen::MatrixXd gram_lower, Method method);

  Eigen::Index size() const { return gram_.rows(); }
  Method method() const { return method_; }
  const Eigen::MatrixXd& gram_lower() const { return gram_; }

  // x = (b G + c I)^-1 r; false (x unspecified) when b G + c I is not
  // numerically positive definite or x is not finite.
  bool solve(double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x);
  // sum_i b l_i / (b l_i + a), a > 0; NaN when b G + a I is not numerically
  // positive definite (cholesky).
  double effective_count(double a, double b);

 private:
  Method method_ = Method::cholesky;
  Eigen::MatrixXd gram_;  // lower triangle of G
  // spectral: G = Q T Q^T and the eigenvalues of T
  Eigen::Tridiagonalization<Eigen::MatrixXd> tridiagonal_;
  Eigen::VectorXd diagonal_, subdiagonal_, eigenvalues_;
  Eigen::VectorXd work_;  // Q^T r, then the tridiagonal solve in place
  Eigen::VectorXd pivots_, multipliers_;
  // cholesky: the damped copy and its factor
  Eigen::MatrixXd damped_;
  Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt_;
};

}  // namespace cnclab
