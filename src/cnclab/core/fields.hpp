#pragma once
// Config fields declared once (DESIGN "field declarations"; STYLE: Hydra
// structured configs, pydantic). An options struct lists each field one time:
// YAML name, member, one-line doc and rule. Reading, emitting (so the
// identity hash of a resolved config), range checks, the JSON Schema
// (`cnclab schema`) and the key tables all loop over that list, so a key can
// never be read without being emitted, or emitted under another name.
//
//   const FieldList<SgdmOptions>& sgdm_fields() {
//     static const auto fields = FieldList<SgdmOptions>()
//         .field("learning_rate", &SgdmOptions::learning_rate, "η > 0 (seed 000 Eq. 14)",
//                Rule::positive())
//         .field("momentum", &SgdmOptions::momentum, "β", Rule::in(0, true, 1, false));
//     return fields;
//   }
//
// Cross-field rules (mu <= mu_max) stay in the struct's validate(), which
// calls check() for the per-field ones.
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/suggest.hpp"

namespace cnclab {

// The rule of one field: numeric bounds, or the allowed strings.
struct Rule {
  struct Bound {
    double value = 0;
    bool inclusive = true;
  };
  std::optional<Bound> min, max;
  std::vector<std::string> choices;  // strings (and string lists): the allowed values
  bool finite = false;               // numbers: NaN and inf are rejected (always, for reals)

  static Rule none() { return {}; }
  // A finite real > 0 / >= 0 / > low.
  static Rule positive() { return above(0); }
  static Rule non_negative() { return at_least(0); }
  static Rule above(double low) { return {Bound{low, false}, std::nullopt, {}, true}; }
  static Rule at_least(double low) { return {Bound{low, true}, std::nullopt, {}, true}; }
  // [low, high], (low, high), [low, high) ... as the flags say.
  static Rule in(double low, bool low_inclusive, double high, bool high_inclusive) {
    return {Bound{low, low_inclusive}, Bound{high, high_inclusive}, {}, true};
  }
  static Rule one_of(std::vector<std::string> names) { return {{}, {}, std::move(names), false}; }

  bool holds(double v) const;
  bool holds(const std::string& v) const;
  // "must be in [0, 1)", "must be a finite number > 0", "must be at least 1",
  // "must be one of: a, b"; "" for none.
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
  section
};

// A declaration without its struct: what the schema and docs need.
struct FieldInfo {
  std::string key, doc;
  FieldKind kind = FieldKind::number;
  Rule rule;
  YAML::Node default_value;         // the default as YAML (sections: the map)
  std::vector<FieldInfo> children;  // section
};

namespace field_detail {

template <class T>
constexpr FieldKind kind_of() {
  if constexpr (std::is_same_v<T, bool>)
    return FieldKind::boolean;
  else if constexpr (std::is_same_v<T, double>)
    return FieldKind::number;
  else if constexpr (std::is_integral_v<T>)
    return FieldKind::integer;
  else if constexpr (std::is_same_v<T, std::string>)
    return FieldKind::string;
  else if constexpr (std::is_same_v<T, std::vector<double>>)
    return FieldKind::number_list;
  else if constexpr (std::is_same_v<T, std::vector<std::string>>)
    return FieldKind::string_list;
  else
    return FieldKind::integer_list;  // std::vector<unsigned integral>
}

// The value as YAML: reals as their shortest round-trip text.
template <class T>
YAML::Node to_node(const T& v) {
  if constexpr (std::is_same_v<T, double>) {
    return YAML::Load(shortest_double(v));
  } else if constexpr (std::is_same_v<T, std::string> || std::is_same_v<T, bool> ||
                       std::is_integral_v<T>) {
    return YAML::Node(v);
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    YAML::Node n(YAML::NodeType::Sequence);
    for (double x : v) n.push_back(to_node(x));
    n.SetStyle(YAML::EmitterStyle::Flow);
    return n;
  } else {  // a std::vector of strings or integers
    YAML::Node n(YAML::NodeType::Sequence);
    for (const auto& x : v) n.push_back(x);
    n.SetStyle(YAML::EmitterStyle::Flow);
    return n;
  }
}

// Checks one value against its rule; OptionError(key, value, rule text).
template <class T>
void check(const std::string& key, const T& v, const Rule& r) {
  constexpr bool integer = std::is_integral_v<T> && !std::is_same_v<T, bool>;
  if constexpr (std::is_same_v<T, double> || integer) {
    if (!r.holds(static_cast<double>(v))) {
      throw OptionError(key, node_text(to_node(v)), r.text(integer));
    }
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!r.holds(v)) throw OptionError(key, v, r.text(false) + did_you_mean(v, r.choices));
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    for (const auto& x : v) {
      if (!r.holds(x)) throw OptionError(key, x, r.text(false) + did_you_mean(x, r.choices));
    }
  } else if constexpr (std::is_same_v<T, std::vector<double>>) {
    for (double x : v) {
      if (!r.holds(x)) throw OptionError(key, node_text(to_node(x)), r.text(false));
    }
  } else if constexpr (!std::is_same_v<T, bool>) {
    for (auto x : v) {
      if (!r.holds(static_cast<double>(x))) {
        throw OptionError(key, std::to_string(x), r.text(true));
      }
    }
  }
}

}  // namespace field_detail

template <class S>
class FieldList {
 public:
  // A scalar or list member. T: double, bool, std::string, std::size_t,
  // std::uint64_t, std::int64_t, or a std::vector of double, std::string,
  // std::size_t.
  template <class T, class Base>
  FieldList&& field(std::string key, T Base::*member, std::string doc, Rule rule = {}) && {
    static_assert(std::is_base_of_v<Base, S>);
    Entry e;
    e.info.key = key;
    e.info.doc = std::move(doc);
    e.info.kind = field_detail::kind_of<T>();
    e.info.rule = rule;
    e.read = [key, member](const ConfigReader& r, S& s) {
      s.*member = r.get<T>(key, static_cast<const T&>(s.*member));
    };
    e.emit = [member](const S& s) { return field_detail::to_node(s.*member); };
    e.check = [key, member, rule](const S& s) { field_detail::check(key, s.*member, rule); };
    entries_.push_back(std::move(e));
    return std::move(*this);
  }

  // A nested map whose fields are declared by `fields` (a FieldList<N>).
  template <class N, class Base>
  FieldList&& section(std::string key, N Base::*member, const FieldList<N>& fields,
                      std::string doc) && {
    static_assert(std::is_base_of_v<Base, S>);
    Entry e;
    e.info.key = key;
    e.info.doc = std::move(doc);
    e.info.kind = FieldKind::section;
    e.nested = [&fields, member](const S& s) { return fields.info(s.*member); };
    e.read = [key, member, &fields](const ConfigReader& r, S& s) {
      fields.read(r.section(key), s.*member);
    };
    e.emit = [member, &fields](const S& s) { return fields.to_node(s.*member); };
    e.check = [key, member, &fields](const S& s) {
      try {
        fields.check(s.*member);
      } catch (const OptionError& err) {
        throw OptionError(key + "." + err.field(), err.value(), err.rule());
      }
    };
    entries_.push_back(std::move(e));
    return std::move(*this);
  }

  // Reads every declared key present in `r` over the values already in `s`
  // (its defaults); absent keys keep them. Does not check rules.
  void read(const ConfigReader& r, S& s) const {
    for (const auto& e : entries_) e.read(r, s);
  }
  // The declared keys in declaration order, as a YAML map.
  YAML::Node to_node(const S& s) const {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& e : entries_) map[e.info.key] = e.emit(s);
    return map;
  }
  // Key/value pairs onto an emitter inside an open map.
  void emit(YAML::Emitter& out, const S& s) const {
    for (const auto& e : entries_) out << YAML::Key << e.info.key << YAML::Value << e.emit(s);
  }
  // Per-field rules; OptionError naming the (dotted) field.
  void check(const S& s) const {
    for (const auto& e : entries_) e.check(s);
  }
  // The declarations with the defaults of `defaults`.
  std::vector<FieldInfo> info(const S& defaults = S{}) const {
    std::vector<FieldInfo> out;
    for (const auto& e : entries_) {
      FieldInfo i = e.info;
      i.default_value = e.emit(defaults);
      if (e.nested) i.children = e.nested(defaults);
      out.push_back(std::move(i));
    }
    return out;
  }
  std::vector<std::string> keys() const {
    std::vector<std::string> k;
    for (const auto& e : entries_) k.push_back(e.info.key);
    return k;
  }

 private:
  struct Entry {
    FieldInfo info;
    std::function<void(const ConfigReader&, S&)> read;
    std::function<YAML::Node(const S&)> emit;
    std::function<void(const S&)> check;
    std::function<std::vector<FieldInfo>(const S&)> nested;
  };
  std::vector<Entry> entries_;
};

}  // namespace cnclab
