#pragma once
// JSON Schema (draft 2020-12) of declared fields (fields.hpp): types, ranges,
// enums, patterns, defaults, required and conditional keys and docs, for
// `cnclab schema` and editors (yaml-language-server).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cnclab/core/field_info.hpp"

namespace cnclab {

// {"type": "object", "properties": {...}, "additionalProperties": false,
// "required": [...]}; a conditional key (FieldInfo::when) adds an if/then to
// "allOf" that forbids it where it does not apply.
nlohmann::json object_schema(const std::vector<FieldInfo>& fields, const std::string& doc = "");

// One field's schema (sections recurse through object_schema).
nlohmann::json field_schema(const FieldInfo& field);

// A YAML default as JSON (scalars typed by the field kind).
nlohmann::json yaml_to_json(const YAML::Node& node);

// One alternative of a map whose keys depend on a tag key (model.type,
// trainer.type, dataset.generator, kind): its name and its own object
// schema (the tag key is added to its properties when missing).
struct TaggedVariant {
  std::string name;
  nlohmann::json schema;
};

// {"properties": {tag: {"enum": names}}, "allOf": [{"if": tag == name,
// "then": variant schema}, ...]}: each variant is checked strictly by its own
// schema. default_tag: the variant an absent tag means ("" = tag required,
// and when it is absent, as in a file whose include sets it, every key must
// be one of some variant's and valid there: "anyOf" of their schemas for it,
// so that misspelt keys are still found).
nlohmann::json tagged_schema(const std::string& tag, const std::string& default_tag,
                             const std::vector<TaggedVariant>& variants,
                             const std::string& doc = "");

// The schema of a file that is only part of a config (its include: supplies
// the rest): `strict` with every "required" list dropped (one inside an "if"
// or a "not" is a condition and stays).
nlohmann::json partial_schema(const nlohmann::json& strict);

// What partial_schema dropped from `strict`, at the same places: its
// "required" lists (with the conditions around them).
// partial_schema(s) and strict_rules(s) together accept what s accepts.
nlohmann::json strict_rules(const nlohmann::json& strict);

// {"type": "object", "description": doc}: any keys (a section whose fields
// are not declared, said so in doc).
nlohmann::json open_schema(const std::string& doc);

}  // namespace cnclab
