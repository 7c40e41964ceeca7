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

#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/field_info.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/suggest.hpp"

namespace cnclab {

namespace field_detail {

template <class T>
struct is_optional : std::false_type {};
template <class T>
struct is_optional<std::optional<T>> : std::true_type {};
template <class T>
struct value_type {
  using type = T;
};
template <class T>
struct value_type<std::optional<T>> {
  using type = T;
};
using Pair = std::array<double, 2>;  // [low, high], low < high

template <class T>
constexpr FieldKind kind_of() {
  if constexpr (is_optional<T>::value)
    return kind_of<typename T::value_type>();
  else if constexpr (std::is_same_v<T, bool>)
    return FieldKind::boolean;
  else if constexpr (std::is_same_v<T, double>)
    return FieldKind::number;
  else if constexpr (std::is_integral_v<T>)
    return FieldKind::integer;
  else if constexpr (std::is_same_v<T, std::string>)
    return FieldKind::string;
  else if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, Pair>)
    return FieldKind::number_list;
  else if constexpr (std::is_same_v<T, std::vector<std::string>>)
    return FieldKind::string_list;
  else
    return FieldKind::integer_list;  // std::vector<unsigned integral>
}

// The value as YAML: reals as their shortest round-trip text.
template <class T>
YAML::Node to_node(const T& v) {
  if constexpr (is_optional<T>::value) {
    return v ? to_node(*v) : YAML::Node();
  } else if constexpr (std::is_same_v<T, double>) {
    return YAML::Load(shortest_double(v));
  } else if constexpr (std::is_same_v<T, std::string> || std::is_same_v<T, bool> ||
                       std::is_integral_v<T>) {
    return YAML::Node(v);
  } else if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, Pair>) {
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

// Reads `key` over `value` (absent: unchanged).
template <class T>
void read(const ConfigReader& r, const std::string& key, T& value) {
  if constexpr (is_optional<T>::value) {
    if (auto v = r.optional<typename T::value_type>(key)) value = std::move(*v);
  } else if constexpr (std::is_same_v<T, Pair>) {
    if (!r.has(key)) return;
    const auto v = r.require<std::vector<double>>(key);
    if (v.size() != 2 || !(v[0] < v[1])) r.fail(key, "must be a list [low, high] with low < high");
    value = {v[0], v[1]};
  } else if constexpr (std::is_same_v<T, int>) {  // read as 64 bits, range-checked
    const std::int64_t v = r.get<std::int64_t>(key, value);
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
      r.fail(key, "is out of the range of an int");
    }
    value = static_cast<int>(v);
  } else {
    value = r.get<T>(key, static_cast<const T&>(value));
  }
}

// Checks one value against its rule; OptionError(key, value, rule text).
template <class T>
void check(const std::string& key, const T& v, const Rule& r) {
  constexpr bool integer = std::is_integral_v<T> && !std::is_same_v<T, bool>;
  if constexpr (is_optional<T>::value) {
    if (v) check(key, *v, r);
  } else if constexpr (std::is_same_v<T, double> || integer) {
    if (!r.holds(static_cast<double>(v))) {
      throw OptionError(key, node_text(to_node(v)), r.text(integer));
    }
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!r.holds(v)) throw OptionError(key, v, r.text(false) + did_you_mean(v, r.choices));
  } else if constexpr (std::is_same_v<T, std::vector<std::string>>) {
    for (const auto& x : v) {
      if (!r.holds(x)) throw OptionError(key, x, r.text(false) + did_you_mean(x, r.choices));
    }
  } else if constexpr (std::is_same_v<T, std::vector<double>> || std::is_same_v<T, Pair>) {
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
  // A scalar or list member. T: double, bool, std::string, int, std::size_t,
  // std::uint64_t, std::int64_t, a std::vector of double, std::string,
  // std::size_t, std::array<double, 2> ([low, high], low < high), or a
  // std::optional of a scalar (absent unless given; emitted only when set).
  template <class T, class Base>
  FieldList&& field(std::string key, T Base::*member, std::string doc, Rule rule = {}) && {
    static_assert(std::is_base_of_v<Base, S>);
    Entry e;
    e.info.key = key;
    e.info.doc = std::move(doc);
    e.info.kind = field_detail::kind_of<T>();
    e.info.rule = rule;
    e.info.optional = field_detail::is_optional<T>::value;
    if constexpr (std::is_same_v<T, field_detail::Pair>) e.info.items = 2;
    e.read = [key, member](const ConfigReader& r, S& s) { field_detail::read(r, key, s.*member); };
    e.emit = [member](const S& s) { return field_detail::to_node(s.*member); };
    e.check = [key, member, rule](const S& s) { field_detail::check(key, s.*member, rule); };
    if constexpr (field_detail::is_optional<T>::value) {
      e.present = [member](const S& s) { return (s.*member).has_value(); };
    }
    entries_.push_back(std::move(e));
    return std::move(*this);
  }

  // An enum member written as one of the names in `names` ({name, value}
  // pairs; every value of the member must have one).
  template <class E, class Base>
  FieldList&& choice(std::string key, E Base::*member, std::vector<std::pair<std::string, E>> names,
                     std::string doc) && {
    static_assert(std::is_base_of_v<Base, S>);
    std::vector<std::string> words;
    for (const auto& n : names) words.push_back(n.first);
    Entry e;
    e.info.key = key;
    e.info.doc = std::move(doc);
    e.info.kind = FieldKind::string;
    e.info.rule = Rule::one_of(words);
    e.read = [key, member, names, words](const ConfigReader& r, S& s) {
      if (!r.has(key)) return;
      const auto text = r.require<std::string>(key);
      for (const auto& [name, value] : names) {
        if (name == text) {
          s.*member = value;
          return;
        }
      }
      r.fail(key, Rule::one_of(words).text(false) + did_you_mean(text, words));
    };
    e.emit = [member, names](const S& s) {
      for (const auto& [name, value] : names) {
        if (value == s.*member) return YAML::Node(name);
      }
      return YAML::Node();  // an undeclared enum value: a bug in the declaration
    };
    e.check = [](const S&) {};
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

  // An optional nested map (std::optional<N>): absent unless given, emitted
  // only when set.
  template <class N, class Base>
  FieldList&& optional_section(std::string key, std::optional<N> Base::*member,
                               const FieldList<N>& fields, std::string doc) && {
    static_assert(std::is_base_of_v<Base, S>);
    Entry e;
    e.info.key = key;
    e.info.doc = std::move(doc);
    e.info.kind = FieldKind::section;
    e.info.optional = true;
    e.nested = [&fields](const S&) { return fields.info(N{}); };
    e.read = [key, member, &fields](const ConfigReader& r, S& s) {
      if (!r.has(key)) return;
      N n{};
      fields.read(r.section(key), n);
      s.*member = std::move(n);
    };
    e.emit = [member, &fields](const S& s) {
      return s.*member ? fields.to_node(*(s.*member)) : YAML::Node();
    };
    e.present = [member](const S& s) { return (s.*member).has_value(); };
    e.check = [key, member, &fields](const S& s) {
      if (s.*member) with_prefix(key, [&] { fields.check(*(s.*member)); });
    };
    entries_.push_back(std::move(e));
    return std::move(*this);
  }

  // A nested map whose fields are members of S itself (YAML groups what the
  // struct keeps flat, e.g. model.dropout.* in MlpOptions).
  FieldList&& group(std::string key, const FieldList<S>& fields, std::string doc) && {
    Entry e;
    e.info.key = key;
    e.info.doc = std::move(doc);
    e.info.kind = FieldKind::section;
    e.nested = [&fields](const S& s) { return fields.info(s); };
    e.read = [key, &fields](const ConfigReader& r, S& s) { fields.read(r.section(key), s); };
    e.emit = [&fields](const S& s) { return fields.to_node(s); };
    e.check = [key, &fields](const S& s) { with_prefix(key, [&] { fields.check(s); }); };
    entries_.push_back(std::move(e));
    return std::move(*this);
  }

  // The fields of a member struct at this level, without a nesting key (a
  // struct shared by several option sets, e.g. ToolPathOptions).
  template <class N, class Base>
  FieldList&& flatten(N Base::*member, const FieldList<N>& fields) && {
    static_assert(std::is_base_of_v<Base, S>);
    for (const auto& inner : fields.entries_) {
      Entry e;
      e.info = inner.info;
      e.read = [member, f = inner.read](const ConfigReader& r, S& s) { f(r, s.*member); };
      e.emit = [member, f = inner.emit](const S& s) { return f(s.*member); };
      e.check = [member, f = inner.check](const S& s) { f(s.*member); };
      if (inner.present)
        e.present = [member, f = inner.present](const S& s) { return f(s.*member); };
      if (inner.nested) e.nested = [member, f = inner.nested](const S& s) { return f(s.*member); };
      entries_.push_back(std::move(e));
    }
    return std::move(*this);
  }

  // A key read and emitted by its own code, declared here so it is known to
  // the schema and the docs: `read` consumes it from the section (over the
  // defaults in s), `emit` gives its resolved value. `info` says its key,
  // doc and kind (FieldKind::any: the schema leaves its shape open unless
  // children are given).
  // `present` (optional): whether it is emitted (never, for keys read by
  // another command).
  FieldList&& custom(FieldInfo info, std::function<void(const ConfigReader&, S&)> read,
                     std::function<YAML::Node(const S&)> emit,
                     std::function<bool(const S&)> present = {}) && {
    Entry e;
    e.info = std::move(info);
    e.read = std::move(read);
    e.emit = std::move(emit);
    e.present = std::move(present);
    e.custom = true;
    e.check = [](const S&) {};
    entries_.push_back(std::move(e));
    return std::move(*this);
  }

  // Modifiers of the field declared last.
  // Must be given (ConfigError "is required" when absent).
  FieldList&& required() && {
    entries_.back().info.required = true;
    return std::move(*this);
  }
  // Applies only while sibling `key` (declared before) is one of `values`
  // (see Condition).
  FieldList&& when(std::string key, std::vector<std::string> values,
                   std::string misplaced = "") && {
    entries_.back().info.when = Condition{std::move(key), std::move(values), std::move(misplaced)};
    return std::move(*this);
  }
  // Applies only while the optional sibling `key` is not set.
  FieldList&& unless_set(std::string key, std::string misplaced = "") && {
    entries_.back().info.when = Condition{std::move(key), {}, std::move(misplaced)};
    return std::move(*this);
  }
  // Emitted only when it differs from the default of S{} (keys added after
  // results exist keep the identity of configs that do not use them).
  FieldList&& omit_default() && {
    Entry& e = entries_.back();
    e.present = [emit = e.emit, d = YAML::Dump(e.emit(S{}))](const S& s) {
      return YAML::Dump(emit(s)) != d;
    };
    return std::move(*this);
  }

  // Reads every declared key present in `r` over the values already in `s`
  // (its defaults); absent keys keep them. Does not check rules.
  void read(const ConfigReader& r, S& s) const {
    for (const auto& e : entries_) {
      const std::string& key = e.info.key;
      if (const Condition* c = failed_condition(e, s)) {
        // (has() marks the key read: without a misplaced text it must stay
        // unread, so that it is reported as an unknown key.)
        if (!c->misplaced.empty() && r.has(key)) r.fail(key, c->misplaced);
        continue;
      }
      if (e.info.required && !e.custom && !r.has(key)) r.fail(key, "is required");
      e.read(r, s);
    }
  }
  // The declared keys that apply and are set, in declaration order, as a
  // YAML map.
  YAML::Node to_node(const S& s) const {
    YAML::Node map(YAML::NodeType::Map);
    for (const auto& e : entries_) {
      if (emitted(e, s)) map[e.info.key] = e.emit(s);
    }
    return map;
  }
  // Key/value pairs onto an emitter inside an open map.
  void emit(YAML::Emitter& out, const S& s) const {
    for (const auto& e : entries_) {
      if (emitted(e, s)) out << YAML::Key << e.info.key << YAML::Value << e.emit(s);
    }
  }
  // The emitted map as block YAML text ending in a newline.
  std::string yaml(const S& s) const {
    YAML::Emitter out;
    out << YAML::BeginMap;
    emit(out, s);
    out << YAML::EndMap;
    return std::string(out.c_str()) + "\n";
  }
  // Per-field rules of the fields that apply; OptionError naming the
  // (dotted) field.
  void check(const S& s) const {
    for (const auto& e : entries_) {
      if (applies(e, s)) e.check(s);
    }
  }
  // The declarations with the defaults of `defaults`.
  std::vector<FieldInfo> info(const S& defaults = S{}) const {
    std::vector<FieldInfo> out;
    for (const auto& e : entries_) {
      FieldInfo i = e.info;
      const bool has_default =
          !i.required && !i.optional && i.kind != FieldKind::any && i.kind != FieldKind::section;
      if (has_default) i.default_value = e.emit(defaults);
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
  template <class>
  friend class FieldList;

  struct Entry {
    FieldInfo info;
    std::function<void(const ConfigReader&, S&)> read;
    std::function<YAML::Node(const S&)> emit;
    std::function<void(const S&)> check;
    std::function<std::vector<FieldInfo>(const S&)> nested;
    std::function<bool(const S&)> present;  // empty: always
    bool custom = false;                    // read by its own code (which checks `required`)
  };

  template <class F>
  static void with_prefix(const std::string& key, F&& f) {
    try {
      f();
    } catch (const OptionError& err) {
      throw OptionError(key + "." + err.field(), err.value(), err.rule());
    }
  }

  // The condition that keeps `e` from applying to `s`, nullptr when it
  // applies. Conditions chain: a field whose sibling does not apply does not
  // apply either, for the sibling's reason (split.train: unless train_count
  // is set, and train_count: while split.mode is random).
  const Condition* failed_condition(const Entry& e, const S& s) const {
    if (!e.info.when) return nullptr;
    const Condition& c = *e.info.when;
    for (const auto& sibling : entries_) {
      if (sibling.info.key != c.key) continue;
      if (const Condition* up = failed_condition(sibling, s)) return up;
      if (c.values.empty()) {
        const bool set = !sibling.present || sibling.present(s);
        return set ? &c : nullptr;
      }
      // The value, also where it is left out of the emitted map as the
      // default (omit_default); an unset optional emits null.
      const YAML::Node v = sibling.emit(s);
      for (const auto& value : c.values) {
        if (v.IsScalar() && v.Scalar() == value) return nullptr;
      }
      return &c;
    }
    throw std::logic_error("field " + e.info.key + ": condition on undeclared key " + c.key);
  }
  bool applies(const Entry& e, const S& s) const { return failed_condition(e, s) == nullptr; }
  bool emitted(const Entry& e, const S& s) const {
    return applies(e, s) && (!e.present || e.present(s));
  }

  std::vector<Entry> entries_;
};

}  // namespace cnclab
