#include "cnclab/train/shifted_gram.hpp"

#include <algorithm>
#include <cmath>

namespace cnclab {

bool ShiftedGram::reset(Eigen::MatrixXd gram_lower, Method method) {
  gram_ = std::move(gram_lower);
  method_ = method;
  const Eigen::Index n = gram_.rows();
  for (Eigen::Index j = 0; j < n; ++j) {
    if (!gram_.col(j).tail(n - j).allFinite()) return false;
  }
  if (method_ == Method::cholesky) return true;
  tridiagonal_.compute(gram_);  // reads the lower triangle
  diagonal_ = tridiagonal_.diagonal();
  subdiagonal_ = tridiagonal_.subDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen;
  eigen.computeFromTridiagonal(diagonal_, subdiagonal_, Eigen::EigenvaluesOnly);
  if (eigen.info() != Eigen::Success) {
    method_ = Method::cholesky;  // the QR iteration did not converge: factor per damping
    return true;
  }
  eigenvalues_ = eigen.eigenvalues().cwiseMax(0.0);  // G is semi-definite: -0 and -eps are 0
  return true;
}

bool ShiftedGram::solve(double b, double c, const Eigen::VectorXd& r, Eigen::VectorXd& x) {
  const Eigen::Index n = gram_.rows();
  if (method_ == Method::cholesky) {
    damped_.resize(n, n);
    damped_.triangularView<Eigen::Lower>() = b * gram_;
    damped_.diagonal().array() += c;
    llt_.compute(damped_);
    if (llt_.info() != Eigen::Success) return false;
    x = llt_.solve(r);
    return x.allFinite();
  }
  // (b T + c I) = L D L^T with L unit lower bidiagonal (multipliers m_i):
  //   D_0 = b t_00 + c,  m_i = b t_{i+1,i} / D_i,  D_{i+1} = b t_{i+1,i+1} + c - m_i b t_{i+1,i};
  // then L y = Q^T r, D z = y, L^T x' = z, x = Q x'.
  work_.noalias() = tridiagonal_.matrixQ().adjoint() * r;
  pivots_.resize(n);
  multipliers_.resize(std::max<Eigen::Index>(n - 1, 0));
  pivots_[0] = b * diagonal_[0] + c;
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    if (!(pivots_[i] > 0) || !std::isfinite(pivots_[i])) return false;
    const double off = b * subdiagonal_[i];
    multipliers_[i] = off / pivots_[i];
    pivots_[i + 1] = b * diagonal_[i + 1] + c - multipliers_[i] * off;
    work_[i + 1] -= multipliers_[i] * work_[i];
  }
  if (!(pivots_[n - 1] > 0) || !std::isfinite(pivots_[n - 1])) return false;
  work_[n - 1] /= pivots_[n - 1];
  for (Eigen::Index i = n - 2; i >= 0; --i) {
    work_[i] = work_[i] / pivots_[i] - multipliers_[i] * work_[i + 1];
  }
  x.noalias() = tridiagonal_.matrixQ() * work_;
  return x.allFinite();
}

double ShiftedGram::effective_count(double a, double b) {
  const Eigen::Index n = gram_.rows();
  if (method_ == Method::spectral) {
    const Eigen::ArrayXd l = b * eigenvalues_.array();
    return (l / (l + a)).sum();
  }
  damped_.resize(n, n);
  damped_.triangularView<Eigen::Lower>() = b * gram_;
  damped_.diagonal().array() += a;
  llt_.compute(damped_);
  if (llt_.info() != Eigen::Success) return std::nan("");
  // tr(A^-1) = ||L^-1||_F^2 for A = L L^T.
  Eigen::MatrixXd l_inv = Eigen::MatrixXd::Identity(n, n);
  llt_.matrixL().solveInPlace(l_inv);
  return static_cast<double>(n) - a * l_inv.squaredNorm();
}

}  // namespace cnclab
