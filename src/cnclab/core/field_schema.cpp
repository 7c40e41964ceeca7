#include "cnclab/core/field_schema.hpp"

#include <algorithm>

namespace cnclab {
namespace {

using nlohmann::json;

// Bounds of integer fields as JSON integers (5, not 5.0).
json bound(double v, bool integer) {
  return integer ? json(static_cast<long long>(v)) : json(v);
}

void add_bounds(json& s, const Rule& r, bool integer = false) {
  if (r.min) s[r.min->inclusive ? "minimum" : "exclusiveMinimum"] = bound(r.min->value, integer);
  if (r.max) s[r.max->inclusive ? "maximum" : "exclusiveMaximum"] = bound(r.max->value, integer);
}

json scalar_schema(FieldKind kind, const Rule& r) {
  json s;
  switch (kind) {
    case FieldKind::number:
    case FieldKind::number_list:
      s["type"] = "number";
      add_bounds(s, r);
      break;
    case FieldKind::integer:
    case FieldKind::integer_list:
      s["type"] = "integer";
      s["minimum"] = 0;  // every integer field is a count or a seed
      add_bounds(s, r, true);
      break;
    case FieldKind::boolean:
      s["type"] = "boolean";
      break;
    case FieldKind::string:
    case FieldKind::string_list:
      s["type"] = "string";
      if (!r.choices.empty()) s["enum"] = r.choices;
      if (!r.pattern.empty()) s["pattern"] = r.pattern;
      break;
    case FieldKind::section:
    case FieldKind::any:
      break;
  }
  return s;
}

// The sibling `key`'s default as a string ("" when it has none).
std::string default_text(const std::vector<FieldInfo>& fields, const std::string& key) {
  for (const auto& f : fields) {
    if (f.key == key && f.default_value.IsDefined() && f.default_value.IsScalar()) {
      return f.default_value.Scalar();
    }
  }
  return "";
}

// Condition `c` of field `key` as JSON Schema: where it does not hold the
// field must be absent (the reader rejects it there, as a misplaced or an
// unknown key).
json condition_schema(const std::vector<FieldInfo>& fields, const std::string& key,
                      const Condition& c) {
  const json absent = {{"not", {{"required", {key}}}}};
  if (c.values.empty()) {
    return {{"if", {{"required", {c.key}}}}, {"then", absent}};
  }
  json cond = {{"properties", {{c.key, {{"enum", c.values}}}}}};
  // An absent sibling takes its default: the condition then holds only if
  // the default is one of the values.
  const std::string d = default_text(fields, c.key);
  if (std::find(c.values.begin(), c.values.end(), d) == c.values.end()) {
    cond["required"] = {c.key};
  }
  return {{"if", cond}, {"else", absent}};
}

}  // namespace

json yaml_to_json(const YAML::Node& node) {
  if (node.IsSequence()) {
    json a = json::array();
    for (const auto& x : node) a.push_back(yaml_to_json(x));
    return a;
  }
  if (node.IsMap()) {
    json o = json::object();
    for (const auto& kv : node) o[kv.first.Scalar()] = yaml_to_json(kv.second);
    return o;
  }
  if (!node.IsScalar()) return nullptr;
  const std::string& text = node.Scalar();
  if (text == "true" || text == "false") return text == "true";
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    if (used == text.size()) {
      if (text.find_first_of(".eE") == std::string::npos) return static_cast<long long>(v);
      return v;
    }
  } catch (const std::exception&) {
  }
  return text;
}

json field_schema(const FieldInfo& f) {
  json s;
  switch (f.kind) {
    case FieldKind::section:
      s = object_schema(f.children, f.doc);
      break;
    case FieldKind::any:
      // Read by its own code. With declared children it is a file name (of
      // a YAML file holding that map, e.g. configs/machines/*.yaml) or the
      // map itself; without, its shape is left open.
      if (f.children.empty()) {
        s = json::object();
      } else {
        s["anyOf"] = json::array({{{"type", "string"}}, object_schema(f.children, f.doc)});
      }
      break;
    case FieldKind::number_list:
    case FieldKind::integer_list:
    case FieldKind::string_list:
      s["type"] = "array";
      s["items"] = scalar_schema(f.kind, f.rule);
      if (f.items) s["minItems"] = s["maxItems"] = f.items;
      break;
    default:
      s = scalar_schema(f.kind, f.rule);
  }
  if (!f.doc.empty()) s["description"] = f.doc;
  if (f.kind != FieldKind::section && f.kind != FieldKind::any && f.default_value.IsDefined() &&
      !f.default_value.IsNull()) {
    s["default"] = yaml_to_json(f.default_value);
  }
  return s;
}

json object_schema(const std::vector<FieldInfo>& fields, const std::string& doc) {
  json s = {{"type", "object"}, {"additionalProperties", false}};
  json props = json::object();
  json required = json::array();
  json conditions = json::array();
  for (const auto& f : fields) {
    props[f.key] = field_schema(f);
    if (f.required) required.push_back(f.key);
    // The field's condition and those of the siblings it depends on (a
    // field applies only where they all hold; fields.hpp).
    for (const FieldInfo* g = &f; g && g->when;) {
      conditions.push_back(condition_schema(fields, f.key, *g->when));
      const std::string& up = g->when->key;
      const auto it = std::find_if(fields.begin(), fields.end(),
                                   [&](const FieldInfo& x) { return x.key == up; });
      g = it == fields.end() ? nullptr : &*it;
    }
  }
  s["properties"] = props;
  if (!required.empty()) s["required"] = required;
  if (!conditions.empty()) s["allOf"] = conditions;
  if (!doc.empty()) s["description"] = doc;
  return s;
}

json tagged_schema(const std::string& tag, const std::string& default_tag,
                   const std::vector<TaggedVariant>& variants, const std::string& doc) {
  json names = json::array();
  json cases = json::array();
  json any_key = json::object();  // per key: the schemas the variants give it
  for (const auto& v : variants) {
    names.push_back(v.name);
    json then = v.schema;
    if (then.contains("properties") && !then["properties"].contains(tag)) {
      then["properties"][tag] = json::object();
    }
    json cond = {{"properties", {{tag, {{"const", v.name}}}}}};
    if (v.name != default_tag) cond["required"] = {tag};
    cases.push_back({{"if", cond}, {"then", then}});
    if (default_tag.empty() && then.contains("properties")) {
      for (const auto& [key, schema] : then["properties"].items()) {
        any_key[key]["anyOf"].push_back(schema);
      }
    }
  }
  json tag_schema = {{"type", "string"}, {"enum", names}};
  if (!default_tag.empty()) tag_schema["default"] = default_tag;
  json s = {{"type", "object"}, {"properties", {{tag, tag_schema}}}, {"allOf", cases}};
  if (default_tag.empty()) {
    s["required"] = {tag};
    // No tag (a file whose include sets it): each key valid in some variant.
    for (auto& [key, schema] : any_key.items()) {
      if (schema["anyOf"].size() == 1) schema = schema["anyOf"][0];
    }
    any_key[tag] = json::object();
    s["allOf"].push_back({{"if", {{"not", {{"required", {tag}}}}}},
                          {"then", {{"properties", any_key}, {"additionalProperties", false}}}});
  }
  if (!doc.empty()) s["description"] = doc;
  return s;
}

namespace {

// The keywords whose values are subschemas (or maps or lists of them) that
// the transforms below walk; "if" and "not" hold conditions and are left as
// they are.
const char* const kSchemaMaps[] = {"properties", "$defs"};
const char* const kSchemaLists[] = {"allOf", "anyOf", "oneOf"};
const char* const kSchemas[] = {"items", "additionalProperties", "then", "else"};

}  // namespace

json partial_schema(const json& strict) {
  if (!strict.is_object()) return strict;
  json s = strict;
  s.erase("required");
  for (const char* k : kSchemaMaps) {
    if (!s.contains(k)) continue;
    for (auto& [name, sub] : s[k].items()) sub = partial_schema(sub);
  }
  for (const char* k : kSchemaLists) {
    if (!s.contains(k)) continue;
    for (auto& sub : s[k]) sub = partial_schema(sub);
  }
  for (const char* k : kSchemas) {
    if (s.contains(k)) s[k] = partial_schema(s[k]);
  }
  return s;
}

json strict_rules(const json& strict) {
  if (!strict.is_object()) return json::object();
  json out = json::object();
  if (strict.contains("required")) out["required"] = strict["required"];
  for (const char* k : kSchemaMaps) {
    if (!strict.contains(k)) continue;
    for (const auto& [name, sub] : strict[k].items()) {
      json r = strict_rules(sub);
      if (!r.empty()) out[k][name] = std::move(r);
    }
  }
  for (const char* k : {"allOf"}) {
    if (!strict.contains(k)) continue;
    for (const auto& sub : strict[k]) {
      json r = strict_rules(sub);
      if (!r.empty()) out[k].push_back(std::move(r));
    }
  }
  // A choice between alternatives holds as a whole (one alternative's
  // requirement cannot be split off): kept as it is when it has any.
  for (const char* k : {"anyOf", "oneOf"}) {
    if (!strict.contains(k)) continue;
    for (const auto& sub : strict[k]) {
      if (!strict_rules(sub).empty()) {
        out[k] = strict[k];
        break;
      }
    }
  }
  for (const char* k : {"items", "additionalProperties"}) {
    if (!strict.contains(k)) continue;
    json r = strict_rules(strict[k]);
    if (!r.empty()) out[k] = std::move(r);
  }
  if (strict.contains("if")) {
    json then = strict.contains("then") ? strict_rules(strict["then"]) : json::object();
    json otherwise = strict.contains("else") ? strict_rules(strict["else"]) : json::object();
    if (!then.empty() || !otherwise.empty()) {
      out["if"] = strict["if"];
      if (!then.empty()) out["then"] = std::move(then);
      if (!otherwise.empty()) out["else"] = std::move(otherwise);
    }
  }
  return out;
}

json open_schema(const std::string& doc) {
  return {{"type", "object"}, {"description", doc}};
}

}  // namespace cnclab
