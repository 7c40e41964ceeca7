#pragma once
// The narx parts of an experiment file (narx_spec.hpp): model, trainer
// stages, and the split and normalisation a narx trial needs. Called by the
// `model` and `trainer` declarations of experiment_fields() (spec.cpp).
#include "cnclab/core/config.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {

// Reads model (type narx) of `root` into `spec`, after its split and
// normalisation: ConfigError unless split.mode is sequential_halves and both
// normalisations are none. A narx experiment's metrics default to the
// registered sequence metrics (sequence_metrics.hpp), so spec.metrics is set
// to them here, before `metrics:` is read over it.
void read_narx_model_section(const ConfigReader& root, ExperimentSpec& spec);

// Reads trainer.stages of `root` into spec.stages; ConfigError when
// trainer.type is given instead of stages.
void read_narx_trainer(const ConfigReader& root, ExperimentSpec& spec);

}  // namespace cnclab
