#pragma once
// The narx parts of an experiment file (narx_spec.hpp): model, trainer
// stages, and the split and normalisation a narx trial needs.
#include "cnclab/core/config.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {

// Reads model (type narx) and trainer.stages into `spec`, after its split and
// normalisation: ConfigError unless split.mode is sequential_halves and both
// normalisations are none, or when trainer.type is given instead of stages.
void read_narx_experiment(const ConfigReader& root, ExperimentSpec& spec);

}  // namespace cnclab
