#pragma once
// The training stage of a run: the experiment's trainer on its network and
// (normalised) training data. Random streams "dropout" and "shuffle" derive
// from the experiment seed (sgdm only; lm and trainbr are deterministic).
#include <Eigen/Core>
#include <cstdint>
#include <functional>

#include "cnclab/experiment/trainer_spec.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/train/summary.hpp"

namespace cnclab {

struct TrainingHooks {
  // Loss on held-out data at the end of each epoch; empty = none.
  std::function<double(const Eigen::VectorXd& params)> validation_loss;
  // After every epoch; returning false stops training.
  std::function<bool(const EpochRecord&, const Eigen::VectorXd& params)> on_epoch;
};

// Trains `params` in place; x: inputs x samples, y: outputs x samples.
Summary train_network(const TrainerSpec& trainer, const Mlp& mlp, const Eigen::MatrixXd& x,
                      const Eigen::MatrixXd& y, Eigen::VectorXd& params, std::uint64_t seed,
                      const TrainingHooks& hooks);

// Bytes the trainer needs beyond the network and data (for memory checks):
// lm/trainbr hold a few N_w x N_w matrices and a block of the Jacobian.
double trainer_workspace_bytes(const TrainerSpec& trainer, double parameters);

}  // namespace cnclab
