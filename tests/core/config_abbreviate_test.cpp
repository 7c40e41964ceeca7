// Large arrays in configs printed for people (config_abbreviate.hpp): the
// threshold, the shape text, the hash against hash_hex of the array's own
// flow text, and everything else kept (checked by parsing both texts).
#include "cnclab/core/config_abbreviate.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <string>

#include "cnclab/core/hash.hpp"

namespace cnclab {
namespace {

// [0, 1, ..., n-1] in flow style.
std::string numbers(std::size_t n) {
  std::string s = "[";
  for (std::size_t i = 0; i < n; ++i) s += (i ? ", " : "") + std::to_string(i);
  return s + "]";
}

// A 16 x 16 x 3 grid of control points in flow style, as an inlined surface has.
std::string grid() {
  std::string s = "[";
  for (int i = 0; i < 16; ++i) {
    s += i ? ", [" : "[";
    for (int j = 0; j < 16; ++j) {
      s += (j ? ", [" : "[") + std::to_string(i) + ", " + std::to_string(j) + ", 0.5]";
    }
    s += "]";
  }
  return s + "]";
}

TEST(ConfigAbbreviate, SmallConfigIsReturnedUnchanged) {
  const std::string text = "name: x\nmodel:\n  hidden: " + numbers(16) + "\n";
  const AbbreviatedConfig a = abbreviate_config(text);
  EXPECT_EQ(a.abbreviated, 0u);
  EXPECT_EQ(a.text, text);  // exactly 16 numbers: at the limit, not over it
}

TEST(ConfigAbbreviate, ArraysOverTheLimitBecomeShapeAndHash) {
  const std::string text =
      "name: x\ndataset:\n  options:\n    surface:\n      degree_u: 3\n"
      "      knots_u: " +
      numbers(17) + "\n      control_points: " + grid() + "\n    lines: 4\n";
  const AbbreviatedConfig a = abbreviate_config(text);
  EXPECT_EQ(a.abbreviated, 2u);
  const YAML::Node in = YAML::Load(text), out = YAML::Load(a.text);
  const YAML::Node surface = out["dataset"]["options"]["surface"];
  // The hash: of the array's flow text, here emitted independently of the code under test.
  const auto flow_hash = [](const YAML::Node& n) {
    YAML::Emitter e;
    e << YAML::Flow << n;
    return hash_hex(e.c_str()).substr(0, 8);
  };
  const YAML::Node surface_in = in["dataset"]["options"]["surface"];
  EXPECT_EQ(surface["control_points"].as<std::string>(),
            "16 × 16 × 3, hash " + flow_hash(surface_in["control_points"]));
  EXPECT_EQ(surface["knots_u"].as<std::string>(),
            "17 values, hash " + flow_hash(surface_in["knots_u"]));
  // Everything else as it was.
  EXPECT_EQ(out["name"].as<std::string>(), "x");
  EXPECT_EQ(surface["degree_u"].as<int>(), 3);
  EXPECT_EQ(out["dataset"]["options"]["lines"].as<int>(), 4);
  EXPECT_LT(a.text.size(), text.size() / 10);
}

TEST(ConfigAbbreviate, EqualArraysShowEqualHashesAndOthersDiffer) {
  const AbbreviatedConfig a =
      abbreviate_config("a: " + numbers(20) + "\nb: " + numbers(20) + "\nc: " + numbers(21) + "\n");
  const YAML::Node out = YAML::Load(a.text);
  EXPECT_EQ(out["a"].as<std::string>(), out["b"].as<std::string>());
  EXPECT_NE(out["a"].as<std::string>().substr(11), out["c"].as<std::string>().substr(11));
}

TEST(ConfigAbbreviate, RaggedArraysAndArraysInsideListsOfMaps) {
  // Ragged: 2 items holding 10 + 9 numbers. A list of maps (trainer.stages)
  // is not an array, but an array inside one of its maps is.
  const std::string text = "ragged: [" + numbers(10) + ", " + numbers(9) +
                           "]\nstages:\n  - {epochs: 5, weights: " + numbers(30) +
                           "}\n  - {epochs: 7}\n";
  const AbbreviatedConfig a = abbreviate_config(text);
  EXPECT_EQ(a.abbreviated, 2u);
  const YAML::Node out = YAML::Load(a.text);
  EXPECT_EQ(out["ragged"].as<std::string>().substr(0, 25), "2 items, 19 values, hash ");
  EXPECT_EQ(out["stages"][0]["epochs"].as<int>(), 5);
  EXPECT_EQ(out["stages"][0]["weights"].as<std::string>().substr(0, 16), "30 values, hash ");
  EXPECT_EQ(out["stages"][1]["epochs"].as<int>(), 7);
}

TEST(ConfigAbbreviate, ThresholdIsAParameterAndBadYamlPassesThrough) {
  EXPECT_EQ(abbreviate_config("a: [1, 2, 3]\n", 2).abbreviated, 1u);
  EXPECT_EQ(abbreviate_config("a: [1, 2\n").text, "a: [1, 2\n");
}

}  // namespace
}  // namespace cnclab
