#pragma once
// The damped Gauss-Newton step of lm and trainbr (lm.hpp, trainbr.hpp),
//   (beta J^T J + c I) dw = -(beta J^T e + alpha w),   c = mu + alpha,
// (lm: alpha = 0, beta = 1) in the shape that is cheaper, for N residuals
// and P parameters:
//  - primal (P x P): G = J^T J, built over row blocks of J
//    (normal_equations.hpp); dw = -(beta G + c I)^-1 (beta J^T e + alpha w).
//  - dual (N x N, for N < P): K = J J^T from J held whole. Woodbury,
//      (c I + beta J^T J)^-1 = (1/c) [I - J^T (J J^T + (c/beta) I)^-1 J],
//    applied to g = beta J^T e + alpha w, with J g = beta K e + alpha J w
//    and (K + s I)^-1 K = I - s (K + s I)^-1 (s = c/beta), gives
//      dw = -(alpha/c) w - beta J^T (beta K + c I)^-1 (e - (alpha/c) J w).
//    w itself is not in the range of J^T (its part orthogonal to the rows
//    of J is only shrunk by the prior), hence the first term; lm's step is
//    dw = -J^T (K + mu I)^-1 e.
// trainbr's effective number of parameters comes from the same Gram matrix:
//   gamma = P - alpha tr((beta J^T J + alpha I)^-1) = sum_i beta l_i / (beta l_i + alpha)
// over the eigenvalues l_i of J^T J, which are those of J J^T and P - N
// zeros (whose terms are 0): the same sum over the N eigenvalues of K.
// The Gram matrix is decomposed once per build (shifted_gram.hpp), so every
// mu tried costs O(n^2) (spectral) or one Cholesky (large n).
//
// Automatic form: dual when N < P, else primal. The dual needs N <= P: with
// more residuals than parameters, J J^T is singular and the part of e
// outside the range of J (the misfit at the optimum, in general) meets
// (K + s I)^-1 = 1/s there: rounding of the order eps ||K|| / s^(3/2) |e|
// enters the step, fatal for lm's small mu (on NIST's Misra1a a forced
// dual ends 1.6e-6 off the certified values after 620 epochs, the primal
// at 1e-11 after 15; docs/performance.md).
#include <Eigen/Core>

#include "cnclab/nn/kernel_table.hpp"
#include "cnclab/train/normal_equations.hpp"
#include "cnclab/train/residual_objective.hpp"
#include "cnclab/train/shifted_gram.hpp"

namespace cnclab {

enum class LmForm { automatic, primal, dual };
enum class LmDecomposition { automatic, spectral, cholesky };

class DampedGaussNewton {
 public:
  // Resolves the form (automatic: dual when N < P) and the decomposition
  // (automatic: ShiftedGram::automatic_method of the form's size). Throws
  // OptionError("form", "dual", ...) for a forced dual with N > P.
  DampedGaussNewton(ResidualObjective& objective, LmForm form, LmDecomposition decomposition,
                    Eigen::Index block_rows = 0);

  LmForm form() const { return form_; }  // primal or dual
  ShiftedGram::Method method() const { return gram_.method(); }

  // e, J^T e, e^T e, the Gram matrix and its decomposition at w. False if
  // a residual, a Jacobian entry or the Gram matrix is not finite.
  bool build(const Eigen::VectorXd& w);
  double sse() const { return sse_; }
  const Eigen::VectorXd& jte() const { return jte_; }
  double max_jtj_diagonal() const { return max_jtj_diagonal_; }

  // The step above at the last build's w; false when the damped system is
  // not numerically positive definite or the step is not finite.
  bool step(double alpha, double beta, double mu, const Eigen::VectorXd& w, Eigen::VectorXd& dw);
  // gamma above; NaN when beta J^T J + alpha I is not numerically positive
  // definite (cholesky).
  double effective_parameters(double alpha, double beta) {
    return gram_.effective_count(alpha, beta);
  }

  // e^T e at w; +Inf if any residual is NaN or Inf.
  double sum_of_squares(const Eigen::VectorXd& w) { return builder_.sum_of_squares(w); }

 private:
  ResidualObjective& objective_;
  LmForm form_;
  ShiftedGram::Method method_;
  NormalEquationBuilder builder_;
  const kernels::Table& kernels_;
  NormalEquations ne_;        // primal: J^T J (then moved into gram_), J^T e, e^T e
  Eigen::MatrixXd jacobian_;  // dual: J, N x P
  Eigen::VectorXd residuals_, jw_, rhs_, y_;
  Eigen::VectorXd jte_;
  double sse_ = 0, max_jtj_diagonal_ = 0;
  ShiftedGram gram_;
};

}  // namespace cnclab
