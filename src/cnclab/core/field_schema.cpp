#include "cnclab/core/field_schema.hpp"

namespace cnclab {
namespace {

using nlohmann::json;

void add_bounds(json& s, const Rule& r) {
  if (r.min) s[r.min->inclusive ? "minimum" : "exclusiveMinimum"] = r.min->value;
  if (r.max) s[r.max->inclusive ? "maximum" : "exclusiveMaximum"] = r.max->value;
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
      add_bounds(s, r);
      break;
    case FieldKind::boolean:
      s["type"] = "boolean";
      break;
    case FieldKind::string:
    case FieldKind::string_list:
      s["type"] = "string";
      if (!r.choices.empty()) s["enum"] = r.choices;
      break;
    case FieldKind::section:
      break;
  }
  return s;
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
    case FieldKind::number_list:
    case FieldKind::integer_list:
    case FieldKind::string_list:
      s["type"] = "array";
      s["items"] = scalar_schema(f.kind, f.rule);
      break;
    default:
      s = scalar_schema(f.kind, f.rule);
  }
  if (!f.doc.empty()) s["description"] = f.doc;
  if (f.kind != FieldKind::section && f.default_value.IsDefined()) {
    s["default"] = yaml_to_json(f.default_value);
  }
  return s;
}

json object_schema(const std::vector<FieldInfo>& fields, const std::string& doc) {
  json s = {{"type", "object"}, {"additionalProperties", false}};
  json props = json::object();
  for (const auto& f : fields) props[f.key] = field_schema(f);
  s["properties"] = props;
  if (!doc.empty()) s["description"] = doc;
  return s;
}

}  // namespace cnclab
