#pragma once
// Levenberg-Marquardt with Bayesian regularisation, MATLAB trainbr semantics
// (MacKay 1992 evidence framework in the Gauss-Newton form of Foresee & Hagan
// 1997, "Gauss-Newton approximation to Bayesian learning"):
//   F(w) = beta E_D + alpha E_W,  E_D = e^T e,  E_W = w^T w  (plain sums);
//   step: (beta J^T J + (mu + alpha) I) dw = -(beta J^T e + alpha w),
//         accepted when F decreases (mu schedule as in lm.hpp);
//   after each accepted step, with J at the new weights:
//     gamma = N_w - alpha tr((beta J^T J + alpha I)^-1),
//     alpha = gamma / (2 E_W),  beta = (N - gamma) / (2 E_D),
//   N = number of residuals (target elements), N_w = number of parameters.
//   Start (as MATLAB): gamma_0 = N_w, beta_0 = (N - gamma_0) / (2 E_D) (1 if
//   that is <= 0 or E_D = 0), alpha_0 = gamma_0 / (2 E_W) (1 if E_W = 0).
// gamma comes from the decomposition of the step's Gram matrix (J^T J, or
// J J^T in the dual form: gauss_newton.hpp) as sum_i beta l_i / (beta l_i +
// alpha) over its eigenvalues, or, for a Gram matrix too large for the
// spectral method, as ||L^-1||_F^2 from the Cholesky factor L of
// beta J^T J + alpha I (no explicit inverse). Guard: when N - gamma <= 0 (few residuals, many
// parameters) beta would not be positive; the previous beta is kept and
// Summary::beta_guard_count says how often. An E_D of 0 gives beta = 1 and an
// E_W of 0 gives alpha = 1 (MATLAB). As MATLAB's trainbr (which forces the
// sse performance), goal is compared with E_D and min_gradient with the data
// term's gradient 2 ||J^T e||. No validation stop.
#include <Eigen/Core>

#include "cnclab/train/lm.hpp"

namespace cnclab {

// trainbr's defaults differ from trainlm's only in the initial mu.
struct TrainbrOptions : LmOptions {
  TrainbrOptions() {  // trainbr: mu 0.005, mu_dec 0.1, mu_inc 10, mu_max 1e10
    mu = 0.005;
    max_fail = 0;  // MATLAB's trainbr disables validation (merges it into training)
  }
};

Summary train_trainbr(ResidualObjective& objective, Eigen::VectorXd& params,
                      const TrainbrOptions& options, const LmHooks& hooks = {});

// `trainer.type: trainbr` (trainer_registry.hpp; lm_trainers.cpp).
TrainerDef trainbr_trainer();

// gamma = N_w - alpha tr((beta J^T J + alpha I)^-1) from the lower triangle of
// J^T J by Cholesky (the reference formula); NaN if beta J^T J + alpha I is
// not positive definite.
double effective_parameters(const Eigen::MatrixXd& jtj_lower, double alpha, double beta);

struct BayesianHyperparameters {
  double alpha = 0;  // weight-decay coefficient
  double beta = 1;   // data coefficient
  double gamma = 0;  // effective number of parameters
};

// One re-estimation (the update rules above) from gamma (before clamping;
// NaN: the factorisation failed and h is left unchanged), N_w = nw, E_D =
// sse, E_W = ssw and N = n at the current weights. gamma is clamped to
// [0, N_w]. Returns false when the beta guard triggered (N - gamma <= 0:
// the previous beta is kept).
bool reestimate_hyperparameters(BayesianHyperparameters& h, double gamma, double nw, double sse,
                                double ssw, double n);

}  // namespace cnclab
