#include "cnclab/train/gauss_newton.hpp"

#include <cmath>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/kernels.hpp"

namespace cnclab {
namespace {

LmForm resolve_form(LmForm form, Eigen::Index n, Eigen::Index p) {
  if (form == LmForm::automatic) return n < p ? LmForm::dual : LmForm::primal;
  if (form == LmForm::dual && n > p) {
    throw OptionError("form", "dual",
                      "needs at most as many residuals as parameters (" + std::to_string(n) +
                          " residuals, " + std::to_string(p) +
                          " parameters): J J^T would be singular; use auto or primal");
  }
  return form;
}

ShiftedGram::Method resolve_method(LmDecomposition d, Eigen::Index size) {
  switch (d) {
    case LmDecomposition::spectral:
      return ShiftedGram::Method::spectral;
    case LmDecomposition::cholesky:
      return ShiftedGram::Method::cholesky;
    case LmDecomposition::automatic:
      break;
  }
  return ShiftedGram::automatic_method(size);
}

}  // namespace

DampedGaussNewton::DampedGaussNewton(ResidualObjective& objective, LmForm form,
                                     LmDecomposition decomposition, Eigen::Index block_rows)
    : objective_(objective),
      form_(resolve_form(form, objective.num_residuals(), objective.num_parameters())),
      method_(resolve_method(decomposition, form_ == LmForm::dual ? objective.num_residuals()
                                                                  : objective.num_parameters())),
      builder_(objective, block_rows),
      kernels_(kernels::active()) {}

bool DampedGaussNewton::build(const Eigen::VectorXd& w) {
  if (form_ == LmForm::primal) {
    if (!builder_.build(w, ne_)) return false;
    jte_ = ne_.jte;
    sse_ = ne_.sse;
    max_jtj_diagonal_ = ne_.jtj.diagonal().maxCoeff();
    return gram_.reset(std::move(ne_.jtj), method_);
  }
  const Eigen::Index n = objective_.num_residuals(), p = objective_.num_parameters();
  jacobian_.resize(n, p);
  residuals_.resize(n);
  objective_.evaluate(w, 0, n, residuals_, &jacobian_);
  if (!residuals_.allFinite() || !jacobian_.allFinite()) return false;
  sse_ = residuals_.squaredNorm();
  if (!std::isfinite(sse_)) return false;
  jte_.setZero(p);
  kernels_.dgemv(true, n, p, jacobian_.data(), n, residuals_.data(), jte_.data());
  jw_.setZero(n);
  kernels_.dgemv(false, n, p, jacobian_.data(), n, w.data(), jw_.data());
  max_jtj_diagonal_ = jacobian_.colwise().squaredNorm().maxCoeff();
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  kernels_.dsyrk(false, n, p, jacobian_.data(), n, k.data(), n);  // lower triangle of J J^T
  return gram_.reset(std::move(k), method_);
}

bool DampedGaussNewton::step(double alpha, double beta, double mu, const Eigen::VectorXd& w,
                             Eigen::VectorXd& dw) {
  const double c = mu + alpha;
  if (form_ == LmForm::primal) {
    rhs_ = -(beta * jte_ + alpha * w);
    return gram_.solve(beta, c, rhs_, dw);
  }
  // dw = -(alpha/c) w - beta J^T (beta K + c I)^-1 (e - (alpha/c) J w)
  const double shrink = alpha / c;
  rhs_ = residuals_ - shrink * jw_;
  if (!gram_.solve(beta, c, rhs_, y_)) return false;
  dw = -shrink * w;
  y_ *= -beta;
  kernels_.dgemv(true, jacobian_.rows(), jacobian_.cols(), jacobian_.data(), jacobian_.rows(),
                 y_.data(), dw.data());
  return dw.allFinite();
}

}  // namespace cnclab
