// `trainer.type: lm` and `trainer.type: trainbr` (trainer_registry.hpp): an
// MLP through MlpResidualObjective, or any residual objective (NARX stages).
#include "cnclab/train/lm.hpp"
#include "cnclab/train/mlp_residuals.hpp"
#include "cnclab/train/trainbr.hpp"
#include "cnclab/train/trainer_registry.hpp"

namespace cnclab {
namespace {

LmHooks lm_hooks(const TrainingHooks& hooks) {
  LmHooks h;
  h.validation_loss = hooks.validation_loss;
  if (hooks.on_epoch) {
    h.on_epoch = [on_epoch = hooks.on_epoch](const EpochRecord& e, const LmEpochRecord&,
                                             const Eigen::VectorXd& p) { return on_epoch(e, p); };
  }
  return h;
}

// `train(options, objective, params, hooks)` on a residual objective, for an
// MLP and for any residual objective.
template <class Options, class Train>
TrainerDef levenberg_marquardt_trainer(std::string name, std::string summary,
                                       const FieldList<LmOptions>& fields, bool validation_stop,
                                       TrainerHistory history, Train train) {
  TrainerCapabilities can;
  can.needs_jacobian = can.deterministic = true;
  can.validation_stop = validation_stop;
  TrainerDef d = make_trainer<Options>(
      std::move(name), std::move(summary), fields, can, history,
      [train](const Options& options, const MlpTrainingProblem& p, Eigen::VectorXd& params) {
        MlpResidualObjective objective(p.mlp, p.x, p.y);
        return train(objective, params, options, lm_hooks(p.hooks));
      });
  d.train_residual = [train](const std::any& options, ResidualObjective& objective,
                             Eigen::VectorXd& params, const LmHooks& hooks) {
    return train(objective, params, std::any_cast<const Options&>(options), hooks);
  };
  // J^T J, the damped copy, its Cholesky factor and L^-1 (trainbr), plus an
  // 8 MB block of J.
  d.workspace_bytes = [](double parameters) {
    return 8.0 * 4.0 * parameters * parameters + 8.0 * 1048576.0;
  };
  return d;
}

}  // namespace

TrainerDef lm_trainer() {
  return levenberg_marquardt_trainer<LmOptions>(
      "lm", "Levenberg-Marquardt, MATLAB trainlm's semantics", lm_fields(), true,
      TrainerHistory::levenberg_marquardt,
      [](ResidualObjective& o, Eigen::VectorXd& w, const LmOptions& t, const LmHooks& h) {
        return train_lm(o, w, t, h);
      });
}

TrainerDef trainbr_trainer() {
  TrainerDef d = levenberg_marquardt_trainer<TrainbrOptions>(
      "trainbr", "Levenberg-Marquardt with Bayesian regularisation, MATLAB trainbr's semantics",
      trainbr_fields(), false, TrainerHistory::bayesian,
      [](ResidualObjective& o, Eigen::VectorXd& w, const TrainbrOptions& t, const LmHooks& h) {
        return train_trainbr(o, w, t, h);
      });
  d.without_validation_stop = "as MATLAB's trainbr";
  return d;
}

}  // namespace cnclab
