// Every declared field is part of a run's identity (issue 16 item 6): for each
// key of each declaration, an override with another valid value must change
// the resolved config (whose hash names the result, so `reproduce` cannot
// reuse a stale result), and the resolved config must read back to itself
// (emit -> read -> emit is a fixed point). The keys come from the
// declarations, not from the emitted text, so a key that is read but not
// emitted fails here.
#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/core/fields.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/sgdm.hpp"
#include "cnclab/train/trainbr.hpp"

namespace cnclab {
namespace {

// A valid value other than the default, as override text; "" when none.
std::string other_value(const FieldInfo& f) {
  const YAML::Node& d = f.default_value;
  switch (f.kind) {
    case FieldKind::boolean:
      return d.as<bool>() ? "false" : "true";
    case FieldKind::integer: {
      const double v = d.as<double>();
      for (double c : {v + 1, v - 1}) {
        if (c >= 0 && f.rule.holds(c)) return std::to_string(static_cast<long long>(c));
      }
      return "";
    }
    case FieldKind::number: {
      const double v = d.as<double>();
      for (double c : {v * 1.5, v * 0.5, v + 0.25, v - 0.25, 0.5, 2.0}) {
        if (c != v && f.rule.holds(c)) return shortest_double(c);
      }
      return "";
    }
    case FieldKind::string:
      for (const auto& c : f.rule.choices) {
        if (c != d.as<std::string>()) return c;
      }
      return "other";
    default:
      return "";  // lists and sections: covered by their own cases
  }
}

// Every scalar leaf of the declarations under `prefix`.
void leaves(const std::vector<FieldInfo>& fields, const std::string& prefix,
            std::vector<std::pair<std::string, FieldInfo>>& out) {
  for (const auto& f : fields) {
    if (f.kind == FieldKind::section) {
      leaves(f.children, prefix + f.key + ".", out);
    } else {
      out.emplace_back(prefix + f.key, f);
    }
  }
}

const std::string kBase =
    "name: t\nseed: 3\ndataset: {generator: friedman1, options: {samples: 50}}\nmodel: {}\n";

void expect_every_key_in_identity(const std::string& trainer_type,
                                  const std::vector<FieldInfo>& fields) {
  const std::string base_yaml = kBase + "trainer: {type: " + trainer_type + "}\n";
  const auto base = parse_experiment(base_yaml, "e.yaml");
  std::vector<std::pair<std::string, FieldInfo>> keys;
  leaves(fields, "trainer.", keys);
  ASSERT_FALSE(keys.empty());
  for (const auto& [key, info] : keys) {
    const std::string value = other_value(info);
    ASSERT_FALSE(value.empty()) << key;
    const auto changed = parse_experiment(base_yaml, "e.yaml", {key + "=" + value});
    EXPECT_NE(hash_hex(changed.resolved_yaml), hash_hex(base.resolved_yaml))
        << trainer_type << ": " << key << "=" << value << " does not change the identity";
    EXPECT_EQ(parse_experiment(changed.resolved_yaml, "r.yaml").resolved_yaml,
              changed.resolved_yaml)
        << key;
  }
}

TEST(FieldIdentity, EveryTrainerKeyChangesTheIdentityAndRoundTrips) {
  expect_every_key_in_identity("sgdm", sgdm_fields().info());
  expect_every_key_in_identity("lm", lm_fields().info());
  expect_every_key_in_identity("trainbr", trainbr_fields().info(TrainbrOptions{}));
}

}  // namespace
}  // namespace cnclab
