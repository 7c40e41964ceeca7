#include "cnclab/experiment/training.hpp"

namespace cnclab {

Summary train_network(const TrainerSpec& trainer, const Mlp& mlp, const Eigen::MatrixXd& x,
                      const Eigen::MatrixXd& y, Eigen::VectorXd& params, std::uint64_t seed,
                      const TrainingHooks& hooks) {
  return trainer.def->train_mlp(trainer.options, MlpTrainingProblem{mlp, x, y, seed, hooks},
                                params);
}

double trainer_workspace_bytes(const TrainerSpec& trainer, double parameters) {
  return trainer.def->workspace_bytes(parameters);
}

}  // namespace cnclab
