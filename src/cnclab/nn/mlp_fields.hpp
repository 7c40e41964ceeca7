#pragma once
// The config fields of an MLP and its initialisers (core/fields.hpp), declared
// beside the options they fill: the experiment's `model:` section reads,
// emits and documents them (experiment/model_spec.hpp), and
// MlpOptions::validate and Initializer::validate check their rules from here.
#include "cnclab/core/fields.hpp"
#include "cnclab/nn/initializer.hpp"
#include "cnclab/nn/mlp.hpp"

namespace cnclab {

// {type: normal, mean, std} | {type: uniform, low, high} | {type: xavier} |
// {type: he}; mean/std only with normal, low/high only with uniform.
const FieldList<Initializer>& initializer_fields();

// `head` (the experiment's model.type key, declared first) followed by the
// MLP's fields: hidden, hidden_activation, output_activation, dropout:
// {keep_probability, placement, inference, mc_samples}, init: {weights,
// biases}. `inputs` and `outputs` are not config fields (they come from the
// dataset).
FieldList<MlpOptions> with_mlp_fields(FieldList<MlpOptions> head);
// The MLP's fields alone (with_mlp_fields of nothing): MlpOptions::validate.
const FieldList<MlpOptions>& mlp_option_fields();

}  // namespace cnclab
