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

}  // namespace
}  // namespace cnclab
