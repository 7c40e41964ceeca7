#include "cnclab/experiment/model_spec.hpp"

#include "cnclab/experiment/narx_spec.hpp"
#include "cnclab/experiment/spec_text.hpp"

namespace cnclab {

const FieldList<Initializer>& initializer_fields() {
  using I = Initializer;
  using K = Initializer::Kind;
  static const auto fields =
      FieldList<I>()
          .choice("type", &I::kind,
                  {{"normal", K::normal},
                   {"uniform", K::uniform},
                   {"xavier", K::xavier},
                   {"he", K::he}},
                  "normal N(mean, std²); uniform U(low, high); xavier U(±√(6/(fan_in + "
                  "fan_out))) (Glorot & Bengio 2010); he N(0, 2/fan_in) (He et al. 2015)")
          .field("mean", &I::mean, "normal: mean", Rule::finite_number())
          .when("type", {"normal"})
          .field("std", &I::std, "normal: standard deviation", Rule::non_negative())
          .when("type", {"normal"})
          .field("low", &I::low, "uniform: lower bound", Rule::finite_number())
          .when("type", {"uniform"})
          .field("high", &I::high, "uniform: upper bound (> low)", Rule::finite_number())
          .when("type", {"uniform"});
  return fields;
}

namespace {

const std::vector<std::pair<std::string, Activation>> kActivations = {
    {"relu", Activation::relu},
    {"tanh", Activation::tanh},
    {"sigmoid", Activation::sigmoid},
    {"linear", Activation::linear}};

const FieldList<MlpOptions>& dropout_fields() {
  using O = MlpOptions;
  static const auto fields =
      FieldList<O>()
          .field("keep_probability", &O::dropout_keep_probability,
                 "probability of keeping a unit (seed 000 Eq. 13: P(r = 1) = p); 1 = no dropout",
                 Rule::in(0, false, 1, true))
          .choice("placement", &O::dropout_placement,
                  {{"between_hidden", DropoutPlacement::between_hidden},
                   {"after_every_hidden", DropoutPlacement::after_every_hidden}},
                  "between_hidden (seed 000) or after_every_hidden")
          .choice(
              "inference", &O::dropout_inference,
              {{"deterministic", DropoutInference::deterministic}, {"mc", DropoutInference::mc}},
              "how the reported predictions and metrics evaluate the network: deterministic "
              "(one pass, r = 1) or mc (Monte-Carlo dropout: the mean of mc_samples passes "
              "with new masks, from the run's own random stream mc_dropout); a network with "
              "dropout is also evaluated the other way, stored beside (the per-epoch losses "
              "and early stopping stay deterministic)")
          .omit_default()
          .field("mc_samples", &O::dropout_mc_samples,
                 "passes averaged by Monte-Carlo dropout (inference mc, and the other-way "
                 "evaluation of a deterministic run)",
                 Rule::in(1, true, 1000000, true))
          .omit_default();
  return fields;
}

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

const FieldList<MlpOptions>& init_fields() {
  using O = MlpOptions;
  static const auto fields =
      FieldList<O>()
          .section("weights", &O::weights, initializer_fields(),
                   "initial weights (seed 000 Eq. 10: N(0, 1))")
          .section("biases", &O::biases, initializer_fields(),
                   "initial biases (seed 000 Eq. 11: U(c, d); ours U(0, 0.1))");
  return fields;
}

}  // namespace

const FieldList<MlpOptions>& mlp_fields() {
  using O = MlpOptions;
  static const auto fields =
      FieldList<O>()
          .custom(
              model_type_info("mlp", "the model: mlp, a multilayer perceptron"),
              [](const ConfigReader& r, O&) { choice(r, "type", "mlp", {"mlp"}); },
              [](const O&) { return YAML::Node("mlp"); })
          .field("hidden", &O::hidden, "hidden layer widths, e.g. [28, 20]",
                 Rule::in(1, true, 100000, true))
          .choice("hidden_activation", &O::hidden_activation, kActivations,
                  "activation of the hidden layers")
          .choice("output_activation", &O::output_activation, kActivations,
                  "activation of the output layer")
          .group("dropout", dropout_fields(), "dropout (seed 000 Eq. 13)")
          .group("init", init_fields(), "initialisers of weights and biases");
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
  r.validate([&] {
    try {
      check.validate();
    } catch (const OptionError& e) {
      const std::string key = e.field() == "dropout_keep_probability" ? "dropout.keep_probability"
                              : e.field() == "dropout_placement"      ? "dropout.placement"
                              : e.field() == "dropout_mc_samples"     ? "dropout.mc_samples"
                                                                      : e.field();
      throw OptionError(key, e.value(), e.rule());
    }
  });
}

}  // namespace cnclab
