// The trochoid job file (kind: gcode) against its declaration:
// every declared key changes the job's identity (its resolved
// config, which names its result) and the resolved config reads back to
// itself.
#include "cnclab/studies/five_axis/trochoid_job.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <map>

#include "cnclab/core/error.hpp"
#include "common/field_leaves.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

const char* kJobFile = CNCLAB_SOURCE_DIR "/experiments/trochoid/groove_table2.yaml";

TEST(TrochoidJob, EveryKeyChangesTheIdentityAndRoundTrips) {
  testing::TempDir dir;
  const std::string base = to_yaml(load_trochoid_job(kJobFile));
  // Values other_value cannot choose: it varies a key from the struct
  // default, which the file may already differ by (feeds), and the job's
  // rules relate keys (D < W).
  const std::map<std::string, std::string> values = {{"trochoid.cutter_diameter", "18"},
                                                     {"program.program_number", "1005"},
                                                     {"program.feed", "1000"},
                                                     {"program.plunge_feed", "250"},
                                                     {"report.compare_with", "other.csv"}};
  std::vector<Leaf> keys;
  leaves(trochoid_job_fields().info(), "", keys);
  ASSERT_GE(keys.size(), 20u);
  for (const auto& leaf : keys) {
    const auto given = values.find(leaf.key);
    const std::string value = given != values.end() ? given->second : other_value(leaf.info);
    ASSERT_FALSE(value.empty()) << leaf.key;
    const std::string changed = to_yaml(load_trochoid_job(kJobFile, {leaf.key + "=" + value}));
    EXPECT_NE(changed, base) << leaf.key << "=" << value << " does not change the identity";
    std::ofstream(dir / "again.yaml") << changed;
    EXPECT_EQ(to_yaml(load_trochoid_job(dir / "again.yaml")), changed) << leaf.key;
  }
}

TEST(TrochoidJob, UnknownAndInvalidKeysAreConfigErrors) {
  EXPECT_THROW(load_trochoid_job(kJobFile, {"program.feeed=1"}), ConfigError);
  EXPECT_THROW(load_trochoid_job(kJobFile, {"entry.mode=spiral"}), ConfigError);
  EXPECT_THROW(load_trochoid_job(kJobFile, {"program.decimals=7"}), ConfigError);
  EXPECT_THROW(load_trochoid_job(kJobFile, {"trochoid.cutter_diameter=30"}), ConfigError);
}

// Rules across sections: the entry must start below the retract height
// (safe_z 5 in the file) and the pass must cut below the stock top.
TEST(TrochoidJob, EntryAboveSafeZAndCutAboveTheStockAreConfigErrors) {
  EXPECT_NO_THROW(load_trochoid_job(kJobFile, {"entry.clearance=4.9"}));
  for (const char* bad : {"entry.clearance=5", "entry.clearance=7"}) {
    try {
      load_trochoid_job(kJobFile, {bad});
      ADD_FAILURE() << bad << " accepted";
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("entry.clearance"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("safe_z = 5"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(load_trochoid_job(kJobFile, {"program.cut_z=0"}), ConfigError);
  EXPECT_THROW(load_trochoid_job(kJobFile, {"program.cut_z=2"}), ConfigError);
}

}  // namespace
}  // namespace cnclab
