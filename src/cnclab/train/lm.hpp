#pragma once
// Levenberg-Marquardt on a residual objective, with MATLAB trainlm's
// semantics and defaults (Hagan & Menhaj 1994; MATLAB Deep Learning Toolbox
// trainlm):
//   solve (J^T J + mu I) dw = -J^T e (in the primal or the dual form, the
//   Gram matrix decomposed once per epoch: gauss_newton.hpp); accept w + dw if the sum of
//   squares E_D = e^T e decreases (then mu <- mu * mu_dec, floored at 1e-20),
//   else mu <- mu * mu_inc and solve again, up to mu_max.
// A step whose damped system is not positive definite or whose objective is NaN/Inf counts as a
// failed step (mu is raised); non-finite values never reach the parameters.
// Stops (checked before every epoch, in MATLAB's order): performance <= goal,
// gradient <= min_gradient, epochs done, max_fail validation checks; and when
// no step with mu <= mu_max decreases F (termination mu_max). Performance and
// gradient are MATLAB's (nntraining.perfs_jejj, R2010b+): trainlm uses the
// network's performance function, by default mse, so performance = E_D / N
// and gradient = 2 ||J^T e|| / N (N residuals); trainbr forces sse, so
// performance = E_D and gradient = 2 ||J^T e|| (the data term's, without
// beta). Validation (lm only; trainbr, as MATLAB's, has no validation
// stop): with a validation loss hook and max_fail > 0, an epoch whose
// validation loss exceeds the best so far is a failed check, a new best
// resets the count, and max_fail consecutive fails stop training
// (termination early_stop); whenever it stops, the parameters of the best
// validation loss (the initial ones included) are returned, as trainlm
// returns best.net.
#include <Eigen/Core>
#include <cstddef>
#include <functional>

#include "cnclab/train/gauss_newton.hpp"
#include "cnclab/train/residual_objective.hpp"
#include "cnclab/train/summary.hpp"

namespace cnclab {

template <class S>
class FieldList;
struct TrainerDef;

struct LmOptions {
  std::size_t epochs = 1000;  // maximum number of accepted steps (trainlm: 1000)
  double goal = 0;            // stop when the performance (above) <= goal (trainlm: 0)
  double mu = 1e-3;           // initial damping mu (trainlm: 0.001)
  double mu_dec = 0.1;        // mu <- mu * mu_dec after a successful step, in (0, 1) (trainlm: 0.1)
  double mu_inc = 10;         // mu <- mu * mu_inc after a failed step, > 1 (trainlm: 10)
  double mu_max = 1e10;       // stop when mu exceeds this (trainlm: 1e10)
  double min_gradient = 1e-7;  // stop when the gradient (above) <= min_gradient (trainlm: 1e-7)
  std::size_t max_fail = 6;    // validation checks (above); 0 = off (trainlm: 6)
  // The shape of the damped system (gauss_newton.hpp): automatic = the
  // N x N dual (J J^T, Woodbury) when there are fewer residuals N than
  // parameters P, else the P x P primal (J^T J); primal or dual forces one
  // (dual needs N <= P).
  LmForm form = LmForm::automatic;
  // Tuning knobs, not part of a config: rows of J per symmetric rank update
  // (primal; 0 = about 8 MB of J), and the decomposition of the Gram matrix
  // (shifted_gram.hpp; automatic = spectral up to 1,024, Cholesky above).
  std::size_t block_rows = 0;
  LmDecomposition decomposition = LmDecomposition::automatic;

  // All finite; epochs >= 1; goal, min_gradient >= 0; 0 < mu <= mu_max;
  // 0 < mu_dec < 1 < mu_inc.
  void validate() const;
};

// The YAML fields of LmOptions (`trainer:` with type lm; block_rows and
// decomposition are tuning knobs, not part of a config), declared once
// (core/fields.hpp);
// validate() checks their rules and mu <= mu_max. trainbr_fields(): the same
// without max_fail (trainbr has no validation stop).
const FieldList<LmOptions>& lm_fields();
const FieldList<LmOptions>& trainbr_fields();

struct LmHooks {
  // Loss on held-out data at the end of each epoch (stored in EpochRecord).
  std::function<double(const Eigen::VectorXd& params)> validation_loss;
  // Called after every epoch; returning false stops training.
  std::function<bool(const EpochRecord&, const LmEpochRecord&, const Eigen::VectorXd& params)>
      on_epoch;
};

// Minimises E_D = e^T e over `params` (updated in place).
Summary train_lm(ResidualObjective& objective, Eigen::VectorXd& params, const LmOptions& options,
                 const LmHooks& hooks = {});

// `trainer.type: lm` (trainer_registry.hpp; lm_trainers.cpp).
TrainerDef lm_trainer();

}  // namespace cnclab
