#include "cnclab/experiment/model_spec.hpp"

#include "cnclab/experiment/narx_spec.hpp"
#include "cnclab/experiment/spec_text.hpp"

namespace cnclab {

namespace {

// The `type` key of a model section that is `type`.
FieldInfo model_type_info(const std::string& type, const std::string& doc) {
  FieldInfo info;
  info.key = "type";
  info.doc = doc;
  info.kind = FieldKind::string;
  info.rule = Rule::one_of({type});
  info.default_value = YAML::Node(type);
  return info;
}

}  // namespace

const FieldList<MlpOptions>& mlp_fields() {
  using O = MlpOptions;
  static const auto fields = with_mlp_fields(FieldList<O>().custom(
      model_type_info("mlp", "the model: mlp, a multilayer perceptron"),
      [](const ConfigReader& r, O&) { choice(r, "type", "mlp", {"mlp"}); },
      [](const O&) { return YAML::Node("mlp"); }));
  return fields;
}

std::vector<ModelType> model_types() {
  return {{"mlp", [] { return mlp_fields().info(); }},
          {"narx", [] {
             auto fields = narx_model_fields().info();
             fields.insert(fields.begin(),
                           model_type_info("narx",
                                           "the model: narx, one NARX network per target "
                                           "(seed 002 Eq. 1), trained in trainer.stages"));
             return fields;
           }}};
}

void validate_mlp_model(const ConfigReader& r, const MlpOptions& m) {
  const ConfigReader init = r.section("init");
  init.section("weights").validate([&] { m.weights.validate(); });
  init.section("biases").validate([&] { m.biases.validate(); });
  // inputs/outputs are set from the dataset; validate the rest with
  // placeholders so a bad value is reported now, not after generation.
  MlpOptions check = m;
  check.inputs = 1;
  check.outputs = 1;
  r.validate([&] { check.validate(); });  // errors name the YAML keys (nn/mlp_fields.hpp)
}

}  // namespace cnclab
