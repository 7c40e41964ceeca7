#pragma once
// The scalar keys of field declarations (core/fields.hpp) with a valid value
// other than each one's default: for tests that change every declared key in
// turn (every key is part of the identity).
#include <string>
#include <vector>

#include "cnclab/core/field_info.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

// A valid value other than the default, as override text; "" when none.
inline std::string other_value(const FieldInfo& f) {
  const YAML::Node& d = f.default_value;
  const bool has_default = d.IsDefined() && !d.IsNull();
  switch (f.kind) {
    case FieldKind::boolean:
      return has_default && d.as<bool>() ? "false" : "true";
    case FieldKind::integer: {
      const double v = has_default ? d.as<double>() : 6;
      for (double c : {v + 1, v - 1}) {
        if (c >= 0 && f.rule.holds(c)) return std::to_string(static_cast<long long>(c));
      }
      return "";
    }
    case FieldKind::number: {
      const double v = has_default ? d.as<double>() : 1;
      for (double c : {v * 1.5, v * 0.5, v + 0.25, v - 0.25, 0.5, 2.0}) {
        if (c != v && f.rule.holds(c)) return shortest_double(c);
      }
      return "";
    }
    case FieldKind::string:
      for (const auto& c : f.rule.choices) {
        if (!has_default || c != d.as<std::string>()) return c;
      }
      return f.rule.choices.empty() ? "other" : "";
    case FieldKind::number_list:
      return f.items == 2 ? "[0.25, 0.5]" : "";
    case FieldKind::integer_list:
      return "[3]";
    case FieldKind::string_list:
      return f.rule.choices.empty() ? "" : "[" + f.rule.choices.front() + "]";
    default:
      return "";  // sections and custom keys: covered by their own cases
  }
}

struct Leaf {
  std::string key;
  FieldInfo info;
  std::vector<std::string> setup;  // overrides that make the key apply
};

// Every scalar leaf of the declarations under `prefix`, with the overrides
// its condition needs.
inline void leaves(const std::vector<FieldInfo>& fields, const std::string& prefix,
                   std::vector<Leaf>& out) {
  for (const auto& f : fields) {
    if (f.kind == FieldKind::section) {
      leaves(f.children, prefix + f.key + ".", out);
      continue;
    }
    Leaf leaf{prefix + f.key, f, {}};
    if (f.when && !f.when->values.empty()) {
      leaf.setup.push_back(prefix + f.when->key + "=" + f.when->values.front());
    }
    out.push_back(leaf);
  }
}

}  // namespace cnclab
