#include "cnclab/experiment/narx_spec.hpp"

#include <algorithm>

#include "cnclab/core/fields.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/suggest.hpp"
#include "cnclab/experiment/spec_text.hpp"

namespace cnclab {

const FieldList<NarxModelSpec>& narx_model_fields() {
  using M = NarxModelSpec;
  static const auto fields =
      FieldList<M>()
          .field("hidden", &M::hidden, "H, hidden units of each axis network (seed 002: 12)",
                 Rule::at_least(1))
          .field("activation", &M::activation, "hidden activation; the output is linear",
                 Rule::one_of({"tanh", "sigmoid", "relu", "linear"}))
          .field("input_delays", &M::input_delays, "D_V, velocity inputs (seed 002: 4)",
                 Rule::at_least(1))
          .field("feedback_delays", &M::feedback_delays,
                 "D_E, fed-back errors e(t-1..t-D_E) (seed 002: 4)", Rule::at_least(1))
          .field("first_input_delay", &M::first_input_delay,
                 "0: v(t) (Eq. 1); 1: MATLAB narxnet(1:D_V, ...)", Rule::in(0, true, 1, true))
          .field("inputs", &M::inputs,
                 "each axis network's input channels, dataset input names without the axis "
                 "suffix (e.g. [v, direction]: v_x, direction_x for e_x); empty: input k for "
                 "target k (seed 002)")
          .omit_default();
  return fields;
}

NarxOptions NarxModelSpec::options() const {
  NarxOptions o;
  o.hidden = hidden;
  o.hidden_activation = parse_activation(activation);
  o.input_delays = input_delays;
  o.feedback_delays = feedback_delays;
  o.first_input_delay = first_input_delay;
  o.inputs = std::max<std::size_t>(inputs.size(), 1);
  return o;
}

const FieldList<StageHead>& stage_fields() {
  static const auto fields =
      FieldList<StageHead>()
          .field("mode", &StageHead::mode,
                 "open_loop: measured errors fed back (series-parallel); closed_loop: the "
                 "network's own "
                 "predictions fed back (parallel, RTRL Jacobian)",
                 Rule::one_of({"open_loop", "closed_loop"}))
          .field(
              "horizon", &StageHead::horizon,
              "closed_loop: predict the series in windows of this many steps, each started from "
              "measured states (0: the whole series in one window, seed 002's parallel training; "
              "docs/narx_training.md)",
              Rule::non_negative())
          .field("fallback_horizon", &StageHead::fallback_horizon,
                 "closed_loop on the whole series: when the stage stops on mu_max or diverges, "
                 "train again from its starting weights on windows of this many steps, then on "
                 "the whole series, and keep the lower whole-series SSE (0: no second try; "
                 "docs/narx_training.md)",
                 Rule::non_negative());
  return fields;
}

std::string to_string(StageMode mode) {
  return mode == StageMode::open_loop ? "open_loop" : "closed_loop";
}

std::string read_model_type(const ConfigReader& model) {
  return choice(model, "type", "mlp", {"mlp", "narx"});
}

NarxModelSpec read_narx_model(const ConfigReader& model) {
  NarxModelSpec m;
  narx_model_fields().read(model, m);
  model.validate([&] {
    narx_model_fields().check(m);
    m.options().validate();
  });
  for (std::size_t i = 0; i < m.inputs.size(); ++i) {
    const std::string& name = m.inputs[i];
    if (name.empty() || name.find('+') != std::string::npos) {
      model.fail("inputs", "entry " + std::to_string(i) + " '" + name +
                               "': must be a non-empty input name without '+'");
    }
    if (std::find(m.inputs.begin(), m.inputs.begin() + static_cast<std::ptrdiff_t>(i), name) !=
        m.inputs.begin() + static_cast<std::ptrdiff_t>(i)) {
      model.fail("inputs", "lists '" + name + "' twice");
    }
  }
  return m;
}

YAML::Node narx_model_to_node(const NarxModelSpec& model) {
  YAML::Node n(YAML::NodeType::Map);
  n["type"] = "narx";
  for (const auto& kv : narx_model_fields().to_node(model)) n[kv.first.Scalar()] = kv.second;
  return n;
}

namespace {

bool needs_jacobian(const TrainerDef& d) {
  return d.capabilities.needs_jacobian;
}

TrainingStage read_stage(const ConfigReader& s) {
  std::vector<std::string> allowed = stage_fields().keys();
  allowed.push_back("type");
  for (const auto& d : trainers().all()) {
    if (!needs_jacobian(d)) continue;
    for (const auto& k : d.keys()) {
      if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) allowed.push_back(k);
    }
  }
  for (const auto& key : s.keys()) {
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (const auto& a : allowed) {
        if (!list.empty()) list += ", ";
        list += a;
      }
      s.fail(key, "unknown key" + did_you_mean(key, allowed) + "; allowed here: " + list);
    }
  }
  StageHead head;
  stage_fields().read(s, head);
  s.validate([&] { stage_fields().check(head); });
  const auto residual = trainer_names(needs_jacobian);
  if (!s.has("type")) s.fail("type", "is required (" + join(residual, " or ") + ")");
  TrainingStage stage;
  stage.mode = head.mode == "closed_loop" ? StageMode::closed_loop : StageMode::open_loop;
  if (head.horizon != 0 && stage.mode == StageMode::open_loop) {
    s.fail("horizon", "applies to closed_loop stages only (an open_loop stage has no windows)");
  }
  stage.horizon = head.horizon;
  if (head.fallback_horizon != 0 && (stage.mode != StageMode::closed_loop || head.horizon != 0)) {
    s.fail("fallback_horizon",
           "applies to closed_loop stages on the whole series only (horizon 0)");
  }
  stage.fallback_horizon = head.fallback_horizon;
  stage.trainer = read_trainer(s, nullptr, needs_jacobian);
  return stage;
}

}  // namespace

std::vector<TrainingStage> read_stages(const ConfigReader& trainer) {
  const YAML::Node list = trainer.raw("stages");
  if (!list.IsSequence() || list.size() == 0) {
    trainer.fail("stages", "must be a non-empty list of stages, e.g. " + stages_example());
  }
  std::vector<TrainingStage> stages;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const YAML::Node item = list[i];
    if (!item.IsMap()) {
      trainer.fail("stages", "entry " + std::to_string(i) + " must be a map {mode, type, ...}");
    }
    stages.push_back(read_stage(trainer.element("stages", i)));
  }
  return stages;
}

YAML::Node stages_to_node(const std::vector<TrainingStage>& stages) {
  YAML::Node list(YAML::NodeType::Sequence);
  for (const auto& stage : stages) {
    YAML::Node node(YAML::NodeType::Map);
    node["mode"] = to_string(stage.mode);
    // Only when set: the identities of results trained before the key existed stay.
    if (stage.horizon != 0) node["horizon"] = stage.horizon;
    if (stage.fallback_horizon != 0) node["fallback_horizon"] = stage.fallback_horizon;
    for (const auto& kv : trainer_to_node(stage.trainer)) node[kv.first.Scalar()] = kv.second;
    node.SetStyle(YAML::EmitterStyle::Flow);  // one line per stage
    list.push_back(node);
  }
  YAML::Node trainer(YAML::NodeType::Map);
  trainer["stages"] = list;
  return trainer;
}

std::string stages_text(const std::vector<TrainingStage>& stages) {
  std::string s;
  for (const auto& stage : stages) {
    if (!s.empty()) s += "+";
    s += to_string(stage.mode) + ":" + trainer_name(stage.trainer);
  }
  return s;
}

std::string stages_example() {
  return "[{mode: open_loop, type: TRAINER, epochs: 150}, {mode: closed_loop, type: TRAINER, "
         "epochs: 40}] (TRAINER: " +
         join(trainer_names(needs_jacobian), " or ") + ")";
}

}  // namespace cnclab
