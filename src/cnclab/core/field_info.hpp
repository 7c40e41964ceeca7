#pragma once
// What a declared config field is, without its struct (fields.hpp declares
// fields of a struct; these are what the JSON Schema, `cnclab schema`, the
// key tables and tests read): its rule, kind, default, doc and when it
// applies.
#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cnclab {

// The rule of one field: numeric bounds, the allowed strings, or a pattern.
struct Rule {
  struct Bound {
    double value = 0;
    bool inclusive = true;
  };
  std::optional<Bound> min, max;
  std::vector<std::string> choices;  // strings (and string lists): the allowed values
  bool finite = false;               // numbers: NaN and inf are rejected (always, for reals)
  // strings: an ECMAScript regular expression the whole value must match
  // (JSON Schema "pattern", anchored here with ^...$), and the rule text.
  std::string pattern, pattern_text;

  static Rule none() { return {}; }
  // A finite real > 0 / >= 0 / > low.
  static Rule positive() { return above(0); }
  static Rule non_negative() { return at_least(0); }
  static Rule above(double low) { return {Bound{low, false}, std::nullopt, {}, true, {}, {}}; }
  static Rule at_least(double low) { return {Bound{low, true}, std::nullopt, {}, true, {}, {}}; }
  // [low, high], (low, high), [low, high) ... as the flags say.
  static Rule in(double low, bool low_inclusive, double high, bool high_inclusive) {
    return {Bound{low, low_inclusive}, Bound{high, high_inclusive}, {}, true, {}, {}};
  }
  static Rule finite_number() { return {std::nullopt, std::nullopt, {}, true, {}, {}}; }
  static Rule one_of(std::vector<std::string> names) {
    return {{}, {}, std::move(names), false, {}, {}};
  }
  static Rule matches(std::string regex, std::string text) {
    return {{}, {}, {}, false, std::move(regex), std::move(text)};
  }

  bool holds(double v) const;
  bool holds(const std::string& v) const;
  // "must be in [0, 1)", "must be a finite number > 0", "must be at least 1",
  // "must be one of: a, b", the pattern text; "" for none.
  std::string text(bool integer) const;
};

// What a field holds, for the schema and the key tables.
enum class FieldKind {
  number,
  integer,
  boolean,
  string,
  number_list,
  integer_list,
  string_list,
  section,
  any  // read by its own code (FieldList::custom): a file name or a map, ...
};

// When a field applies. `key` is a sibling declared before it. With
// `values`: while the sibling's value is one of them; without: while the
// (optional) sibling is not set. A field that does not apply is neither read
// nor emitted; given anyway, it is an error with the rule `misplaced`, or an
// unknown key when `misplaced` is empty. Conditions chain: while the sibling
// itself does not apply, neither does the field.
struct Condition {
  std::string key;
  std::vector<std::string> values;
  std::string misplaced;
};

// A declaration without its struct: what the schema and docs need.
struct FieldInfo {
  std::string key, doc;
  FieldKind kind = FieldKind::number;
  Rule rule;
  YAML::Node default_value;         // the default as YAML (sections: the map); undefined: none
  std::vector<FieldInfo> children;  // section
  bool required = false;            // no default: the file must give it
  bool optional = false;            // no default: absent unless given (std::optional member)
  std::size_t items = 0;            // lists of a fixed length (e.g. [low, high]: 2); 0 = any
  std::optional<Condition> when;    // conditional key
};

// The declaration of a key read by its own code (FieldList::custom).
inline FieldInfo custom_info(std::string key, std::string doc, FieldKind kind = FieldKind::any,
                             Rule rule = {}) {
  FieldInfo i;
  i.key = std::move(key);
  i.doc = std::move(doc);
  i.kind = kind;
  i.rule = std::move(rule);
  return i;
}

}  // namespace cnclab
