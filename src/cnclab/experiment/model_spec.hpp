#pragma once
// model: the network block of an experiment, one declaration (FieldList,
// core/fields.hpp) per model type: mlp_fields() here, narx_model_fields() in
// narx_spec.hpp. `model.type` picks the type; each type's
// keys are declared once and serve the reader, the resolved config (so the
// identity hash), `cnclab schema` and the key tables.
//
// Adding a model type: declare its FieldList beside its options, list it in
// model_types() (the schema gets an if/then on `type` for it), read it in
// the experiment reader (spec.cpp: read_model_section) and use it in
// runner.cpp.
#include <functional>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/nn/initializer.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/nn/mlp_fields.hpp"

namespace cnclab {

// model: {type: mlp, then the MLP's fields (with_mlp_fields, nn/mlp_fields.hpp)};
// `inputs`/`outputs` come from the dataset at run time.
const FieldList<MlpOptions>& mlp_fields();

struct ModelType {
  std::string type;                                // the value of model.type
  std::function<std::vector<FieldInfo>()> fields;  // its declared keys, `type` included
};

// The model types an experiment file may name, in the order the schema lists them.
std::vector<ModelType> model_types();

// Validates the options read from a `model: {type: mlp, ...}` section `r`
// (placeholders for inputs/outputs, set from the dataset later); errors name
// the YAML keys.
void validate_mlp_model(const ConfigReader& r, const MlpOptions& m);

}  // namespace cnclab
