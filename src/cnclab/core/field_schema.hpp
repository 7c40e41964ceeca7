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
// schema. default_tag: the variant an absent tag means ("" = tag required).
nlohmann::json tagged_schema(const std::string& tag, const std::string& default_tag,
                             const std::vector<TaggedVariant>& variants,
                             const std::string& doc = "");

// {"type": "object", "description": doc}: any keys (a section whose fields
// are not declared, said so in doc).
nlohmann::json open_schema(const std::string& doc);

}  // namespace cnclab
