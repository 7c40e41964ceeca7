#include "cnclab/experiment/training.hpp"

#include <type_traits>

#include "cnclab/core/rng.hpp"
#include "cnclab/train/mlp_residuals.hpp"
#include "cnclab/train/objective.hpp"

namespace cnclab {

Summary train_network(const TrainerSpec& trainer, const Mlp& mlp, const Eigen::MatrixXd& x,
                      const Eigen::MatrixXd& y, Eigen::VectorXd& params, std::uint64_t seed,
                      const TrainingHooks& hooks) {
  if (const auto* sgdm = std::get_if<SgdmOptions>(&trainer)) {
    Rng dropout_rng(seed, "dropout");
    Rng shuffle_rng(seed, "shuffle");
    MlpRegressionObjective objective(mlp, x, y, dropout_rng);
    return train_sgdm(objective, params, *sgdm, shuffle_rng,
                      SgdmHooks{hooks.validation_loss, hooks.on_epoch});
  }
  MlpResidualObjective objective(mlp, x, y);
  LmHooks lm_hooks;
  lm_hooks.validation_loss = hooks.validation_loss;
  if (hooks.on_epoch) {
    lm_hooks.on_epoch = [&](const EpochRecord& e, const LmEpochRecord&, const Eigen::VectorXd& p) {
      return hooks.on_epoch(e, p);
    };
  }
  if (const auto* br = std::get_if<TrainbrOptions>(&trainer)) {
    return train_trainbr(objective, params, *br, lm_hooks);
  }
  return train_lm(objective, params, std::get<LmOptions>(trainer), lm_hooks);
}

double trainer_workspace_bytes(const TrainerSpec& trainer, double parameters) {
  if (!is_levenberg_marquardt(trainer)) return 0;
  // J^T J, the damped copy, its Cholesky factor and L^-1 (trainbr), plus an
  // 8 MB block of J.
  return 8.0 * 4.0 * parameters * parameters + 8.0 * 1048576.0;
}

}  // namespace cnclab
