#include "cnclab/experiment/experiment_schema.hpp"

#include <stdexcept>

#include "cnclab/core/error.hpp"
#include "cnclab/core/field_schema.hpp"
#include "cnclab/data/generator_registry.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/model_spec.hpp"
#include "cnclab/experiment/narx_spec.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace {

using nlohmann::json;

constexpr const char* kDraft = "https://json-schema.org/draft/2020-12/schema";

// One schema per registered trainer that passes `allowed`, each with the
// keys `head` before its own.
std::vector<TaggedVariant> trainer_variants(const std::vector<FieldInfo>& head,
                                            bool (*allowed)(const TrainerDef&)) {
  std::vector<TaggedVariant> variants;
  for (const auto& d : trainers().all()) {
    if (allowed && !allowed(d)) continue;
    std::vector<FieldInfo> fields = head;
    const auto own = d.fields();
    fields.insert(fields.end(), own.begin(), own.end());
    variants.push_back({d.name, object_schema(fields)});
  }
  return variants;
}

// One entry of trainer.stages: its own keys (mode) and those of its type.
json stage_schema() {
  const auto residual = [](const TrainerDef& d) { return d.capabilities.needs_jacobian; };
  const auto names = trainer_names(residual);
  return tagged_schema(
      "type", "", trainer_variants(stage_fields().info(), residual),
      "one training stage (" + join(names, " or ") + "), from the previous stage's weights");
}

// trainer: {type, ...} or, for model.type narx, {stages: [...]} alone (the
// if/then of train_file_schema says which one a file needs).
json trainer_schema(const std::string& doc) {
  json s = tagged_schema("type", "", trainer_variants({}, nullptr), doc);
  s.erase("required");
  // Without a type (stages, or a type from an include) the keys of every
  // type are checked: stages is one of them.
  for (auto& c : s["allOf"]) {
    if (c["if"].contains("not")) c["then"]["properties"]["stages"] = json::object();
  }
  s["properties"]["stages"] = {
      {"description", "model.type narx: the training stages, run in order (narx_spec.hpp), e.g. " +
                          stages_example()},
      {"type", "array"},
      {"minItems", 1},
      {"items", stage_schema()}};
  s["allOf"].push_back(
      {{"if", {{"required", {"stages"}}}},
       {"then", {{"properties", {{"stages", json::object()}}}, {"additionalProperties", false}}}});
  return s;
}

json metrics_schema(const std::vector<std::string>& names) {
  return {{"type", "array"}, {"items", {{"type", "string"}, {"enum", names}}}};
}

// What model.type narx needs elsewhere in the file (spec_narx.hpp): trainer
// stages, split.mode sequential_halves, no normalisation, sequence metrics;
// any other model needs trainer.type and takes the regression metrics.
void add_model_rules(json& s) {
  const json is_narx = {
      {"properties",
       {{"model", {{"properties", {{"type", {{"const", "narx"}}}}}, {"required", {"type"}}}}}},
      {"required", {"model"}}};
  const json none = {{"const", "none"}};
  s["if"] = is_narx;
  s["then"] = {
      {"properties",
       {{"trainer", {{"required", {"stages"}}}},
        {"split",
         {{"properties", {{"mode", {{"const", "sequential_halves"}}}}}, {"required", {"mode"}}}},
        {"normalisation",
         {{"properties", {{"inputs", none}, {"targets", none}}},
          {"required", {"inputs", "targets"}}}},
        {"metrics",
         metrics_schema(metric_selection_names(sequence_metric_names(), {"validation"}))}}},
      {"required", {"split", "normalisation"}}};
  s["else"] = {
      {"properties",
       {{"trainer", {{"required", {"type"}}}},
        {"metrics", metrics_schema(metric_selection_names(base_metrics(), metric_splits()))}}}};
  std::vector<std::string> all = metric_selection_names(base_metrics(), metric_splits());
  for (const auto& m : metric_selection_names(sequence_metric_names(), {"validation"})) {
    all.push_back(m);
  }
  s["properties"]["metrics"]["items"]["enum"] = all;
}

// model: {type, ...}; without a type each key is checked against every
// type's (a file whose include sets the type, e.g. a narx variant giving
// model.inputs only), and a file without include: reads a missing type as
// mlp (train_file_schema adds that rule).
json model_schema(const std::string& doc) {
  std::vector<TaggedVariant> variants;
  for (const auto& m : model_types()) variants.push_back({m.type, object_schema(m.fields())});
  json s = tagged_schema("type", "", variants, doc);
  s.erase("required");
  s["properties"]["type"]["default"] = "mlp";
  return s;
}

// The default model type of a file without include: (the reader's default).
json default_model_rule() {
  for (const auto& m : model_types()) {
    if (m.type != "mlp") continue;
    json model;
    model["if"] = {{"not", {{"required", {"type"}}}}};
    model["then"] = object_schema(m.fields());
    json rule;
    rule["if"] = {{"not", {{"required", {"include"}}}}};
    rule["then"]["properties"]["model"] = model;
    return rule;
  }
  throw std::logic_error("model_types() lists no mlp");
}

// dataset: the generator picks the schema of `options`.
json dataset_schema(const std::vector<FieldInfo>& dataset_info, const std::string& doc) {
  std::vector<TaggedVariant> variants;
  for (const auto& g : known_generators()) {
    std::vector<FieldInfo> fields = dataset_info;
    for (auto& f : fields) {
      if (f.key != "options") continue;
      f.doc = "options of " + g.name + " (" + g.summary + ")";
      if (g.options) {
        f.kind = FieldKind::section;
        f.children = g.options();
      } else {
        f.doc += "; not declared yet: any keys pass here, `cnclab validate` checks them";
      }
    }
    variants.push_back({g.name, object_schema(fields)});
  }
  return tagged_schema("generator", "", variants, doc);
}

// Keys every file may have, handled by the config loader (core/config.hpp).
void add_loader_keys(json& s) {
  s["properties"]["include"] = {
      {"description",
       "YAML fragment(s) merged first (paths relative to the file, or configs/...); the file's "
       "own keys override them"},
      {"anyOf",
       json::array({{{"type", "string"}}, {{"type", "array"}, {"items", {{"type", "string"}}}}})}};
  s["properties"]["profiles"] = {
      {"description",
       "named override sets, e.g. {quick: {trainer.epochs: 20}}, applied by --profile NAME; "
       "never part of the resolved config"},
      {"type", "object"},
      {"additionalProperties",
       {{"type", "object"},
        {"properties",
         {{"profile.exclusive",
           {{"description",
             "a setting, not an override: reproduce --profile NAME runs only the files that "
             "define NAME"},
            {"type", "boolean"}}}}}}}};
}

// A file with include: gets any key from its includes, so nothing is
// required of it (partial_schema: its keys are still checked, misspelt ones
// fail); a file without include: gets all of `strict` (strict_rules).
json with_include_rule(const json& strict) {
  json s = partial_schema(strict);
  s["allOf"].push_back(
      {{"if", {{"not", {{"required", {"include"}}}}}}, {"then", strict_rules(strict)}});
  return s;
}

json with_header(json s, const std::string& title) {
  s["$schema"] = kDraft;
  s["title"] = title;
  return s;
}

}  // namespace

json train_file_schema(const std::vector<FieldInfo>& sweep_block,
                       const std::vector<FieldInfo>& slurm_block) {
  const auto info = experiment_fields().info();
  json s = object_schema(info, "a training experiment (kind: train, the default)");
  for (const auto& f : info) {
    if (f.key == "dataset") s["properties"]["dataset"] = dataset_schema(f.children, f.doc);
    if (f.key == "model") s["properties"]["model"] = model_schema(f.doc);
    if (f.key == "trainer") s["properties"]["trainer"] = trainer_schema(f.doc);
    if (f.key == "sweep") {
      s["properties"]["sweep"] = sweep_block.empty()
                                     ? open_schema(f.doc + "; checked by `cnclab sweep`")
                                     : object_schema(sweep_block, f.doc);
    }
    if (f.key == "slurm") {
      s["properties"]["slurm"] = slurm_block.empty() ? open_schema(f.doc + "; checked by `--slurm`")
                                                     : object_schema(slurm_block, f.doc);
    }
  }
  // The reader requires what the experiment is about (no silent defaults).
  for (const char* key : {"dataset", "model", "trainer"}) s["required"].push_back(key);
  s["allOf"].push_back(default_model_rule());
  add_model_rules(s);
  add_loader_keys(s);
  return s;
}

json experiment_file_schema(const std::string& kind, const std::vector<FieldInfo>& sweep_block,
                            const std::vector<FieldInfo>& slurm_block) {
  std::vector<TaggedVariant> variants = {
      {"train", with_include_rule(train_file_schema(sweep_block, slurm_block))}};
  for (const auto& k : registered_job_kinds()) {
    json s = k.schema ? k.schema()
                      : open_schema("kind " + k.kind + " (" + k.summary +
                                    "): its keys are not declared yet; any keys pass here, "
                                    "`cnclab validate FILE` checks them");
    if (s.contains("properties")) {
      add_loader_keys(s);
      s = with_include_rule(s);
    }
    variants.push_back({k.kind, s});
  }
  if (!kind.empty()) {
    for (const auto& v : variants) {
      if (v.name == kind) return with_header(v.schema, "cnclab experiment file, kind " + kind);
    }
    std::string known;
    for (const auto& v : variants) known += (known.empty() ? "" : ", ") + v.name;
    throw ConfigError("--kind " + kind + ": unknown kind; known: " + known);
  }
  return with_header(
      tagged_schema("kind", "train", variants,
                    "a cnclab experiment file; `kind` (default train) picks its keys"),
      "cnclab experiment file");
}

}  // namespace cnclab
