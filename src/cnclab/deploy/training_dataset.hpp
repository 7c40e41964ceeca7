#pragma once
// The dataset a model was trained on, found again: the result's own dataset
// file when it still holds the same content (its content hash), else the
// dataset cache, where it is generated from the result's resolved dataset
// section and generator seed when absent.
#include "cnclab/data/dataset.hpp"
#include "cnclab/deploy/deployed_model.hpp"

namespace cnclab {

// Error naming the result when the dataset made from its config is not the
// one it trained on (another content hash: the generator changed since).
Dataset training_dataset(const DeployedModel& model, const TrainingDataOptions& options);

}  // namespace cnclab
