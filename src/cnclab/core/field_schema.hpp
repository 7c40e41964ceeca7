#pragma once
// JSON Schema (draft 2020-12) of declared fields (fields.hpp): types, ranges,
// enums, defaults and docs, for `cnclab schema` and editors
// (yaml-language-server).
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cnclab/core/fields.hpp"

namespace cnclab {

// {"type": "object", "properties": {...}, "additionalProperties": false}.
nlohmann::json object_schema(const std::vector<FieldInfo>& fields, const std::string& doc = "");

// One field's schema (sections recurse through object_schema).
nlohmann::json field_schema(const FieldInfo& field);

// A YAML default as JSON (scalars typed by the field kind).
nlohmann::json yaml_to_json(const YAML::Node& node);

}  // namespace cnclab
