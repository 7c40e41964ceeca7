#include "cnclab/experiment/experiment_schema.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/field_schema.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/model_spec.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {
namespace {

using nlohmann::json;

constexpr const char* kDraft = "https://json-schema.org/draft/2020-12/schema";

json trainer_schema(const std::string& doc) {
  return tagged_schema("type", "",
                       {{"sgdm", object_schema(sgdm_fields().info())},
                        {"lm", object_schema(lm_fields().info())},
                        {"trainbr", object_schema(lm_fields().info(TrainbrOptions{}))}},
                       doc);
}

json model_schema(const std::string& doc) {
  std::vector<TaggedVariant> variants;
  for (const auto& m : model_types()) variants.push_back({m.type, object_schema(m.fields())});
  return tagged_schema("type", "mlp", variants, doc);
}

// dataset: the generator picks the schema of `options`.
json dataset_schema(const std::vector<FieldInfo>& dataset_info, const std::string& doc) {
  std::vector<TaggedVariant> variants;
  for (const auto& g : builtin_generators()) {
    std::vector<FieldInfo> fields = dataset_info;
    for (auto& f : fields) {
      if (f.key != "options") continue;
      f.doc = "options of " + g.name + " (" + g.summary + ")";
      if (g.options) {
        f.kind = FieldKind::section;
        f.children = g.options();
      } else {
        f.doc +=
            "; not declared yet (issue 16 item 6): any keys pass here, `cnclab validate` "
            "checks them";
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
      {"additionalProperties", {{"type", "object"}}}};
}

json with_header(json s, const std::string& title) {
  s["$schema"] = kDraft;
  s["title"] = title;
  return s;
}

}  // namespace

json train_file_schema() {
  const auto info = experiment_fields().info();
  json s = object_schema(info, "a training experiment (kind: train, the default)");
  for (const auto& f : info) {
    if (f.key == "dataset") s["properties"]["dataset"] = dataset_schema(f.children, f.doc);
    if (f.key == "model") s["properties"]["model"] = model_schema(f.doc);
    if (f.key == "trainer") s["properties"]["trainer"] = trainer_schema(f.doc);
    if (f.key == "sweep") {
      s["properties"]["sweep"] = open_schema(
          f.doc + "; its keys are not declared yet (issue 16 item 6): checked by `cnclab sweep`");
    }
  }
  // The reader requires what the experiment is about (no silent defaults).
  for (const char* key : {"dataset", "model", "trainer"}) s["required"].push_back(key);
  add_loader_keys(s);
  return s;
}

json experiment_file_schema(const std::string& kind) {
  std::vector<TaggedVariant> variants = {{"train", train_file_schema()}};
  for (const auto& k : registered_job_kinds()) {
    json s = k.schema ? k.schema()
                      : open_schema("kind " + k.kind + " (" + k.summary +
                                    "): its keys are not declared yet (issue 16 item 6); any "
                                    "keys pass here, `cnclab validate FILE` checks them");
    if (s.contains("properties")) add_loader_keys(s);
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
