// Field declarations (core/fields.hpp) on a toy struct: reading over
// defaults, emitting in declaration order, rule texts and checks, nested
// sections, and the JSON Schema they produce, each checked against values
// written out by hand here.
#include "cnclab/core/fields.hpp"

#include <gtest/gtest.h>

#include "cnclab/core/field_schema.hpp"

namespace cnclab {
namespace {

struct Inner {
  double ratio = 0.5;
};

struct Toy {
  double rate = 0.1;
  std::size_t count = 2;
  bool flag = true;
  std::string mode = "fast";
  std::vector<std::size_t> sizes = {3, 4};
  Inner inner;
};

const FieldList<Inner>& inner_fields() {
  static const auto f =
      FieldList<Inner>().field("ratio", &Inner::ratio, "a share", Rule::in(0, true, 1, false));
  return f;
}

const FieldList<Toy>& toy_fields() {
  static const auto f = FieldList<Toy>()
                            .field("rate", &Toy::rate, "step", Rule::positive())
                            .field("count", &Toy::count, "how many", Rule::at_least(1))
                            .field("flag", &Toy::flag, "on or off")
                            .field("mode", &Toy::mode, "speed", Rule::one_of({"fast", "slow"}))
                            .field("sizes", &Toy::sizes, "widths", Rule::at_least(1))
                            .section("inner", &Toy::inner, inner_fields(), "nested");
  return f;
}

Toy read_toy(const std::string& yaml) {
  const ConfigDocument doc = ConfigDocument::parse(yaml, "t.yaml");
  Toy t;
  toy_fields().read(doc.root(), t);
  doc.check_all_consumed();
  return t;
}

std::string emitted(const Toy& t) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  toy_fields().emit(out, t);
  out << YAML::EndMap;
  return out.c_str();
}

TEST(Fields, ReadOverDefaultsAndEmitInDeclarationOrder) {
  const Toy t = read_toy("count: 5\ninner: {ratio: 0.25}\n");
  EXPECT_EQ(t.rate, 0.1);  // absent: the default stays
  EXPECT_EQ(t.count, 5u);
  EXPECT_EQ(t.inner.ratio, 0.25);
  EXPECT_EQ(emitted(t),
            "rate: 0.1\ncount: 5\nflag: true\nmode: fast\nsizes: [3, 4]\ninner:\n  ratio: 0.25");
  // emit -> read -> emit is a fixed point.
  EXPECT_EQ(emitted(read_toy(emitted(t))), emitted(t));
}

TEST(Fields, UndeclaredKeysAreLeftForTheUnknownKeyCheck) {
  try {
    read_toy("rat: 1\n");
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("rat: unknown key (did you mean 'rate'?)"),
              std::string::npos)
        << e.what();
  }
}

TEST(Fields, RuleTextsAndChecks) {
  EXPECT_EQ(Rule::positive().text(false), "must be a finite number > 0");
  EXPECT_EQ(Rule::non_negative().text(false), "must be a finite number >= 0");
  EXPECT_EQ(Rule::above(1).text(false), "must be a finite number > 1");
  EXPECT_EQ(Rule::in(0, true, 1, false).text(false), "must be in [0, 1)");
  EXPECT_EQ(Rule::in(0, false, 1, false).text(false), "must be in (0, 1)");
  EXPECT_EQ(Rule::at_least(1).text(true), "must be at least 1");
  EXPECT_EQ(Rule::one_of({"a", "b"}).text(false), "must be one of: a, b");
  EXPECT_FALSE(Rule::in(0, true, 1, false).holds(1.0));
  EXPECT_TRUE(Rule::in(0, true, 1, false).holds(0.0));
  EXPECT_FALSE(Rule::positive().holds(std::nan("")));

  Toy t;
  t.inner.ratio = 1.0;
  try {
    toy_fields().check(t);
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "inner.ratio");
    EXPECT_EQ(e.rule(), "must be in [0, 1)");
  }
  t = Toy{};
  t.sizes = {3, 0};
  EXPECT_THROW(toy_fields().check(t), OptionError);
  t = Toy{};
  t.mode = "medium";
  EXPECT_THROW(toy_fields().check(t), OptionError);
  EXPECT_NO_THROW(toy_fields().check(Toy{}));
}

TEST(Fields, SchemaHasTypesBoundsEnumsDefaultsAndDocs) {
  const nlohmann::json s = object_schema(toy_fields().info());
  const nlohmann::json expected = nlohmann::json::parse(R"({
    "type": "object", "additionalProperties": false,
    "properties": {
      "rate": {"type": "number", "exclusiveMinimum": 0, "default": 0.1, "description": "step"},
      "count": {"type": "integer", "minimum": 1, "default": 2, "description": "how many"},
      "flag": {"type": "boolean", "default": true, "description": "on or off"},
      "mode": {"type": "string", "enum": ["fast", "slow"], "default": "fast",
               "description": "speed"},
      "sizes": {"type": "array", "items": {"type": "integer", "minimum": 1},
                "default": [3, 4], "description": "widths"},
      "inner": {"type": "object", "additionalProperties": false, "description": "nested",
                "properties": {"ratio": {"type": "number", "minimum": 0, "exclusiveMaximum": 1,
                                         "default": 0.5, "description": "a share"}}}
    }})");
  EXPECT_EQ(s, expected) << s.dump(2);
}

// The extensions: optional members, enums, conditional keys, defaults left
// out of the emitted map, groups, optional sections and [low, high] pairs.
enum class Shape { round, square };

struct Options {
  std::optional<std::size_t> count;
  double share = 0.5;
  Shape shape = Shape::round;
  double radius = 1;
  std::array<double, 2> range = {-1.0, 1.0};
  bool extra = false;
  std::string id = "a";
  double group_value = 2;
  std::optional<Inner> inner;
};

const FieldList<Options>& group_fields() {
  static const auto f = FieldList<Options>().field("value", &Options::group_value, "in a group");
  return f;
}

const FieldList<Options>& options_fields() {
  using O = Options;
  static const auto f =
      FieldList<O>()
          .field("count", &O::count, "how many (instead of share)")
          .field("share", &O::share, "a share", Rule::in(0, true, 1, true))
          .unless_set("count", "give count or share, not both")
          .choice("shape", &O::shape, {{"round", Shape::round}, {"square", Shape::square}}, "form")
          .field("radius", &O::radius, "round only", Rule::positive())
          .when("shape", {"round"})
          .field("range", &O::range, "[low, high]")
          .when("shape", {"square"}, "applies to square only")
          .field("extra", &O::extra, "left out when false")
          .omit_default()
          .field("id", &O::id, "an identifier",
                 Rule::matches("^[a-z]+$", "must be lower-case letters"))
          .group("group", group_fields(), "a group")
          .optional_section("inner", &O::inner, inner_fields(), "optional");
  return f;
}

Options read_options(const std::string& yaml) {
  const ConfigDocument doc = ConfigDocument::parse(yaml, "o.yaml");
  Options o;
  options_fields().read(doc.root(), o);
  doc.check_all_consumed();
  return o;
}

std::string emitted(const Options& o) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  options_fields().emit(out, o);
  out << YAML::EndMap;
  return out.c_str();
}

std::string error_of(const std::string& yaml) {
  try {
    read_options(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Fields, OptionalConditionalAndOmittedKeys) {
  // Defaults: count unset, so share applies; round, so radius applies.
  EXPECT_EQ(emitted(Options{}), "share: 0.5\nshape: round\nradius: 1\nid: a\ngroup:\n  value: 2");
  const Options o = read_options(
      "count: 4\nshape: square\nrange: [0, 2]\nextra: true\ngroup: {value: 3}\ninner: {ratio: "
      "0.75}\n");
  EXPECT_EQ(o.count, std::optional<std::size_t>(4));
  EXPECT_EQ(o.shape, Shape::square);
  EXPECT_EQ(o.range[1], 2.0);
  EXPECT_EQ(o.group_value, 3.0);
  ASSERT_TRUE(o.inner.has_value());
  EXPECT_EQ(o.inner->ratio, 0.75);
  EXPECT_EQ(emitted(o),
            "count: 4\nshape: square\nrange: [0, 2]\nextra: true\nid: a\ngroup:\n  value: "
            "3\ninner:\n  ratio: 0.75");
  EXPECT_EQ(emitted(read_options(emitted(o))), emitted(o));  // a fixed point
}

TEST(Fields, KeysWhereTheyDoNotApplyAreErrors) {
  EXPECT_NE(error_of("count: 3\nshare: 0.2\n").find("share = 0.2: give count or share, not both"),
            std::string::npos)
      << error_of("count: 3\nshare: 0.2\n");
  EXPECT_NE(error_of("range: [0, 1]\n").find("applies to square only"), std::string::npos);
  // No misplaced text: an unknown key.
  EXPECT_NE(error_of("shape: square\nradius: 2\n").find("radius: unknown key"), std::string::npos);
  EXPECT_NE(error_of("shape: oval\n").find("must be one of: round, square"), std::string::npos);
  EXPECT_NE(error_of("shape: square\nrange: [1, 0]\n").find("low < high"), std::string::npos);
  Options bad;
  bad.id = "A1";
  try {
    options_fields().check(bad);
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "id");
    EXPECT_EQ(e.rule(), "must be lower-case letters");
  }
}

TEST(Fields, SchemaOfConditionalAndOptionalKeys) {
  const nlohmann::json s = object_schema(options_fields().info());
  EXPECT_FALSE(s["properties"]["count"].contains("default"));  // optional: no default
  EXPECT_EQ(s["properties"]["range"]["minItems"], 2);
  EXPECT_EQ(s["properties"]["range"]["maxItems"], 2);
  EXPECT_EQ(s["properties"]["id"]["pattern"], "^[a-z]+$");
  EXPECT_EQ(s["properties"]["shape"]["enum"], nlohmann::json::array({"round", "square"}));
  EXPECT_EQ(s["properties"]["group"]["properties"]["value"]["default"], 2);
  EXPECT_EQ(s["properties"]["inner"]["additionalProperties"], false);
  // share is forbidden once count is given; radius only with round (the
  // default: an absent shape is round); range only with square (not the
  // default: shape must be given).
  const nlohmann::json expected = nlohmann::json::parse(R"([
    {"if": {"required": ["count"]}, "then": {"not": {"required": ["share"]}}},
    {"if": {"properties": {"shape": {"enum": ["round"]}}},
     "else": {"not": {"required": ["radius"]}}},
    {"if": {"properties": {"shape": {"enum": ["square"]}}, "required": ["shape"]},
     "else": {"not": {"required": ["range"]}}}])");
  EXPECT_EQ(s["allOf"], expected) << s["allOf"].dump(2);
}

// Conditions chain (split: train applies unless train_count is set, and
// train_count only while mode is random, the default, left out when
// emitted).
struct Chained {
  std::string mode = "random";
  std::optional<std::size_t> count;
  double share = 0.5;
};

const FieldList<Chained>& chained_fields() {
  using C = Chained;
  static const auto f =
      FieldList<C>()
          .field("mode", &C::mode, "random or halves", Rule::one_of({"random", "halves"}))
          .omit_default()
          .field("count", &C::count, "a count")
          .when("mode", {"random"}, "applies to mode random only")
          .field("share", &C::share, "a share")
          .unless_set("count", "give count or share, not both");
  return f;
}

std::string chained(const std::string& yaml) {
  const ConfigDocument doc = ConfigDocument::parse(yaml, "c.yaml");
  Chained c;
  try {
    chained_fields().read(doc.root(), c);
    doc.check_all_consumed();
  } catch (const ConfigError& e) {
    return e.what();
  }
  YAML::Emitter out;
  out << YAML::BeginMap;
  chained_fields().emit(out, c);
  out << YAML::EndMap;
  return out.c_str();
}

TEST(Fields, ConditionsChain) {
  // An omitted default still satisfies a condition on its value.
  EXPECT_EQ(chained("{}"), "share: 0.5");
  EXPECT_EQ(chained("count: 3\n"), "count: 3");
  EXPECT_EQ(chained("mode: halves\n"), "mode: halves");
  // share depends on count, which does not apply: share does not either,
  // for count's reason.
  EXPECT_NE(chained("mode: halves\nshare: 0.2\n").find("share = 0.2: applies to mode random only"),
            std::string::npos)
      << chained("mode: halves\nshare: 0.2\n");
  EXPECT_NE(chained("mode: halves\ncount: 2\n").find("applies to mode random only"),
            std::string::npos);
  EXPECT_NE(chained("count: 3\nshare: 0.2\n").find("not both"), std::string::npos);
  // The schema forbids share where count may not be given, too.
  const nlohmann::json s = object_schema(chained_fields().info());
  const nlohmann::json expected = nlohmann::json::parse(R"([
    {"if": {"properties": {"mode": {"enum": ["random"]}}},
     "else": {"not": {"required": ["count"]}}},
    {"if": {"required": ["count"]}, "then": {"not": {"required": ["share"]}}},
    {"if": {"properties": {"mode": {"enum": ["random"]}}},
     "else": {"not": {"required": ["share"]}}}])");
  EXPECT_EQ(s["allOf"], expected) << s["allOf"].dump(2);
}

}  // namespace
}  // namespace cnclab
