// train_lm and train_trainbr: one damped Gauss-Newton loop; trainbr adds the
// alpha/beta re-estimation after every accepted step (formulas in trainbr.hpp).
#include <chrono>
#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/trainbr.hpp"

namespace cnclab {
namespace {

// MATLAB trainlm/trainbr floor mu at 1e-20 after a successful step.
constexpr double kMuFloor = 1e-20;

std::string text(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

Summary levenberg_marquardt(ResidualObjective& objective, Eigen::VectorXd& params,
                            const LmOptions& o, bool bayesian, const LmHooks& hooks,
                            const char* name) {
  o.validate();
  if (params.size() != objective.num_parameters()) {
    throw Error(std::string(name) + ": " + std::to_string(params.size()) +
                " parameters given, objective has " + std::to_string(objective.num_parameters()));
  }
  const auto start = std::chrono::steady_clock::now();
  const Eigen::Index nw = objective.num_parameters();
  const double n = static_cast<double>(objective.num_residuals());
  DampedGaussNewton system(objective, o.form, o.decomposition,
                           static_cast<Eigen::Index>(o.block_rows));
  Summary summary;
  if (!params.allFinite() || !system.build(params)) {
    summary.termination = Termination::diverged;
    summary.message = "residuals or Jacobian not finite at the initial parameters";
    return summary;
  }
  double ssw = params.squaredNorm();
  BayesianHyperparameters reg;  // lm: alpha 0, beta 1 throughout
  reg.gamma = static_cast<double>(nw);
  if (bayesian) {
    reg.beta = system.sse() == 0 ? 1.0 : (n - reg.gamma) / (2.0 * system.sse());
    if (!(reg.beta > 0)) reg.beta = 1.0;
    reg.alpha = ssw == 0 ? 1.0 : reg.gamma / (2.0 * ssw);
  }
  double f = reg.beta * system.sse() + reg.alpha * ssw;
  double mu = o.mu;
  // MATLAB's performance and gradient (lm.hpp): mse for trainlm, sse for trainbr.
  const double per_residual = bayesian ? 1.0 : 1.0 / n;
  const auto gradient_now = [&] { return 2.0 * system.jte().norm() * per_residual; };
  const auto snapshot = [&] {
    LmEpochRecord lm;
    lm.sse = system.sse();
    lm.ssw = ssw;
    lm.alpha = reg.alpha;
    lm.beta = reg.beta;
    lm.gamma = reg.gamma;
    lm.mu = mu;
    lm.gradient = gradient_now();
    lm.curvature = reg.beta * system.max_jtj_diagonal();
    return lm;
  };
  summary.lm_initial = snapshot();

  // Validation checks (lm.hpp): the best validation loss and its parameters.
  const bool validating = !bayesian && o.max_fail > 0 && hooks.validation_loss;
  double best_validation = INFINITY;
  std::size_t best_epoch = 0, fails = 0;
  Eigen::VectorXd best_params;
  if (validating) {
    best_validation = hooks.validation_loss(params);
    if (!std::isfinite(best_validation)) best_validation = INFINITY;
    best_params = params;
  }

  Eigen::VectorXd step(nw), trial(nw);
  std::size_t epochs_done = 0;
  const auto stop = [&](Termination t, std::string message) {
    summary.termination = t;
    if (validating && best_epoch != epochs_done) {
      params = best_params;  // as trainlm returns best.net
      message += "; the parameters of epoch " + std::to_string(best_epoch) +
                 " (best validation loss) are returned";
    }
    summary.message = std::move(message);
    return summary;
  };

  for (std::size_t epoch = 1;; ++epoch) {
    const std::string after = " after " + std::to_string(epoch - 1) + " epochs";
    if (system.sse() * per_residual <= o.goal) {
      return stop(Termination::goal, "performance goal met" + after);
    }
    if (gradient_now() <= o.min_gradient) {
      return stop(Termination::min_gradient, "minimum gradient reached" + after);
    }
    if (epoch > o.epochs) return stop(Termination::max_epochs, "maximum epoch reached" + after);
    if (validating && fails >= o.max_fail) {
      return stop(Termination::early_stop, "validation stop: " + std::to_string(fails) +
                                               " epochs without a better validation loss" + after);
    }

    // One accepted step, raising mu until F decreases.
    bool accepted = false;
    double sse_new = 0, ssw_new = 0;
    while (mu <= o.mu_max) {
      if (system.step(reg.alpha, reg.beta, mu, params, step)) {
        trial = params + step;
        sse_new = system.sum_of_squares(trial);
        ssw_new = trial.squaredNorm();
        const double f_new = reg.beta * sse_new + reg.alpha * ssw_new;
        if (std::isfinite(f_new) && f_new < f) {
          accepted = true;
          break;
        }
      }
      mu *= o.mu_inc;
    }
    if (!accepted) {
      return stop(Termination::mu_max, "mu exceeded mu_max without a decrease of the objective" +
                                           after + " (converged to rounding or stuck)");
    }
    params.swap(trial);
    epochs_done = epoch;
    ssw = ssw_new;
    mu = std::max(mu * o.mu_dec, kMuFloor);
    if (!system.build(params)) {
      return stop(Termination::diverged, "Jacobian not finite in epoch " + std::to_string(epoch));
    }
    if (bayesian &&
        !reestimate_hyperparameters(reg, system.effective_parameters(reg.alpha, reg.beta),
                                    static_cast<double>(nw), system.sse(), ssw, n)) {
      ++summary.beta_guard_count;
    }
    f = reg.beta * system.sse() + reg.alpha * ssw;

    EpochRecord record;
    record.epoch = epoch;
    record.train_loss = system.sse() / n;
    record.validation_loss = hooks.validation_loss ? hooks.validation_loss(params) : std::nan("");
    record.wall_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const LmEpochRecord lm = snapshot();
    if (validating) {
      if (record.validation_loss < best_validation) {
        best_validation = record.validation_loss;
        best_epoch = epoch;
        best_params = params;
        fails = 0;
      } else if (!(record.validation_loss <= best_validation)) {  // worse, or not finite
        ++fails;
      }
    }
    summary.history.push_back(record);
    summary.lm_history.push_back(lm);
    if (hooks.on_epoch && !hooks.on_epoch(record, lm, params)) {
      return stop(Termination::stopped_by_callback,
                  "stopped by callback after epoch " + std::to_string(epoch));
    }
  }
}

}  // namespace

const FieldList<LmOptions>& trainbr_fields() {
  using O = LmOptions;
  static const auto fields =
      FieldList<O>()
          .field("epochs", &O::epochs, "maximum accepted steps (trainlm/trainbr: 1000)",
                 Rule::at_least(1))
          .field("goal", &O::goal,
                 "stop when the performance <= goal (lm: E_D/N, MATLAB's mse; trainbr: E_D)",
                 Rule::non_negative())
          .field("mu", &O::mu, "initial damping μ (trainlm: 0.001, trainbr: 0.005)",
                 Rule::positive())
          .field("mu_dec", &O::mu_dec, "μ ← μ·mu_dec after a successful step, in (0, 1)",
                 Rule::in(0, false, 1, false))
          .field("mu_inc", &O::mu_inc, "μ ← μ·mu_inc after a failed step, > 1", Rule::above(1))
          .field("mu_max", &O::mu_max,
                 "stop when no step with μ <= mu_max lowers the objective (1e10)", Rule::positive())
          .field("min_gradient", &O::min_gradient,
                 "stop when the gradient <= min_gradient (lm: 2‖Jᵀe‖/N, MATLAB's mse; trainbr: "
                 "2‖Jᵀe‖) (1e-7)",
                 Rule::non_negative())
          .choice("form", &O::form,
                  {{"auto", LmForm::automatic}, {"primal", LmForm::primal}, {"dual", LmForm::dual}},
                  "shape of the damped system: auto = the N × N dual JJᵀ (Woodbury) when there "
                  "are fewer residuals N than parameters P, else the P × P primal JᵀJ; primal or "
                  "dual forces one (dual needs N <= P); both give the same steps to rounding");
  return fields;
}

const FieldList<LmOptions>& lm_fields() {
  using O = LmOptions;
  static const auto fields =
      FieldList<O>(trainbr_fields())
          .field("max_fail", &O::max_fail,
                 "stop after this many epochs in a row without a better validation loss and "
                 "return the best (trainlm: 6; 0 = off; needs a validation split)",
                 Rule::non_negative());
  return fields;
}

void LmOptions::validate() const {
  lm_fields().check(*this);
  if (mu > mu_max) throw OptionError("mu", text(mu), "must not exceed mu_max = " + text(mu_max));
}

double effective_parameters(const Eigen::MatrixXd& jtj_lower, double alpha, double beta) {
  ShiftedGram gram;
  if (!gram.reset(jtj_lower, ShiftedGram::Method::cholesky)) return std::nan("");
  return gram.effective_count(alpha, beta);
}

bool reestimate_hyperparameters(BayesianHyperparameters& h, double gamma, double nw, double sse,
                                double ssw, double n) {
  if (!std::isfinite(gamma)) return true;  // keep alpha, beta: factorisation failed
  h.gamma = std::min(std::max(gamma, 0.0), nw);
  h.alpha = ssw == 0 ? 1.0 : h.gamma / (2.0 * ssw);
  if (sse == 0) {
    h.beta = 1.0;
  } else if (n - h.gamma > 0) {
    h.beta = (n - h.gamma) / (2.0 * sse);
  } else {
    return false;  // beta guard: keep the previous beta
  }
  return true;
}

Summary train_lm(ResidualObjective& objective, Eigen::VectorXd& params, const LmOptions& options,
                 const LmHooks& hooks) {
  return levenberg_marquardt(objective, params, options, false, hooks, "lm");
}

Summary train_trainbr(ResidualObjective& objective, Eigen::VectorXd& params,
                      const TrainbrOptions& options, const LmHooks& hooks) {
  return levenberg_marquardt(objective, params, options, true, hooks, "trainbr");
}

}  // namespace cnclab
