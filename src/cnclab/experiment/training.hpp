#pragma once
// The training stage of a run: the experiment's trainer (trainer_spec.hpp,
// train/trainer_registry.hpp) on its network and (normalised) training data.
// A trainer's random streams derive from the experiment seed.
#include <Eigen/Core>
#include <cstdint>

#include "cnclab/experiment/trainer_spec.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/train/summary.hpp"
#include "cnclab/train/trainer_registry.hpp"

namespace cnclab {

// Trains `params` in place; x: inputs x samples, y: outputs x samples.
Summary train_network(const TrainerSpec& trainer, const Mlp& mlp, const Eigen::MatrixXd& x,
                      const Eigen::MatrixXd& y, Eigen::VectorXd& params, std::uint64_t seed,
                      const TrainingHooks& hooks);

// Bytes the trainer needs beyond the network and data (for memory checks).
double trainer_workspace_bytes(const TrainerSpec& trainer, double parameters);

}  // namespace cnclab
