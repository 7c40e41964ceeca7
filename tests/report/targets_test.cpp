// Declared targets (report/targets.hpp): the manifest's `targets:` list read
// strictly, each comparison against hand-picked values on both sides of its
// bound, profiles, and `tables NAME --check` / `reproduce`'s table check
// through a registered table with known measurements.
#include "cnclab/report/targets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::error_message;

void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

std::size_t count(const std::string& text, const std::string& word) {
  std::size_t n = 0;
  for (auto at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

// A table whose measurements are fixed: a count and a share.
const Measurements kMeasured = {{"fake.surface1.test_samples", 5940},
                                {"fake.surface1.share_below_0.5um", 99.71},
                                {"fake.surface2.share_below_1um", 99.8}};

const TableEntry& fake_table() {
  static const TableEntry entry = [] {
    TableEntry e{"fake-targets", "a table for targets_test",
                 [](const TablesOptions&, std::ostream& out) { out << "fake table\n"; },
                 [](const TablesOptions&) { return kMeasured; }, "studies/fake.yaml"};
    register_table(e);
    return e;
  }();
  return entry;
}

TEST(Targets, ComparisonsHoldExactlyOnTheirSide) {
  EXPECT_TRUE(holds(TargetOp::ge, 99.5, 99.5));
  EXPECT_FALSE(holds(TargetOp::ge, 99.49, 99.5));
  EXPECT_TRUE(holds(TargetOp::le, 1.0, 1.0));
  EXPECT_FALSE(holds(TargetOp::lt, 1.0, 1.0));
  EXPECT_TRUE(holds(TargetOp::lt, 0.99, 1.0));
  EXPECT_TRUE(holds(TargetOp::gt, 2, 1));
  EXPECT_TRUE(holds(TargetOp::eq, 5940, 5940));
  EXPECT_FALSE(holds(TargetOp::eq, 5941, 5940));
  // A missing measurement (NaN) never passes, whatever the operator.
  for (TargetOp op : {TargetOp::ge, TargetOp::le, TargetOp::eq, TargetOp::lt, TargetOp::gt}) {
    EXPECT_FALSE(holds(op, NAN, 1.0)) << to_string(op);
  }
}

TEST(Targets, ReadsEntriesAndProfileValues) {
  testing::TempDir dir;
  const fs::path file = dir / "m.yaml";
  write(file,
        "variants: {}\n"
        "targets:\n"
        "  - {name: a.b, op: \">=\", value: 99.5, source: \"seed 000\"}\n"
        "  - name: c\n"
        "    op: \"==\"\n"
        "    value: 5940\n"
        "    profiles: {quick: 5940}\n"
        "    source: paper\n");
  const auto t = read_targets(file);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0].name, "a.b");
  EXPECT_EQ(t[0].op, TargetOp::ge);
  EXPECT_EQ(t[0].value, 99.5);
  EXPECT_EQ(t[0].value_for(""), 99.5);
  EXPECT_FALSE(t[0].value_for("quick"));  // declared for the full study only
  EXPECT_EQ(t[1].value_for("quick"), 5940);
  EXPECT_NE(t[1].where.find("m.yaml:4:"), std::string::npos) << t[1].where;
  EXPECT_NE(t[1].where.find("targets[1]"), std::string::npos) << t[1].where;
  // A manifest without targets has none.
  write(file, "variants: {}\n");
  EXPECT_TRUE(read_targets(file).empty());
}

TEST(Targets, MalformedEntriesAreConfigErrors) {
  testing::TempDir dir;
  const fs::path file = dir / "m.yaml";
  const auto message = [&](const std::string& entry) {
    write(file, "targets:\n  - " + entry + "\n");
    return error_message<ConfigError>([&] { read_targets(file); });
  };
  EXPECT_NE(message("{name: a, op: \"=>\", value: 1, source: s}").find("targets[0].op"),
            std::string::npos);
  EXPECT_NE(message("{name: a, op: \"<\", value: 1}").find("targets[0].source"), std::string::npos);
  const std::string typo = message("{name: a, op: \"<\", value: 1, source: s, sorce: t}");
  EXPECT_NE(typo.find("targets[0].sorce"), std::string::npos) << typo;
  EXPECT_NE(typo.find("unknown key"), std::string::npos) << typo;
  EXPECT_NE(message("{name: a, op: \"<\", value: .nan, source: s}").find("targets[0].value"),
            std::string::npos);
  write(file, "targets: {name: a}\n");
  EXPECT_NE(error_message<ConfigError>([&] { read_targets(file); }).find("must be a list"),
            std::string::npos);
}

TEST(Targets, UnknownNameNamesFileKeyAndNeighbours) {
  testing::TempDir dir;
  const fs::path file = dir / "m.yaml";
  write(file,
        "targets:\n  - {name: fake.surface1.share_below_05um, op: \">=\", value: 1, "
        "source: s}\n");
  const auto targets = read_targets(file);
  const std::string m = error_message<ConfigError>([&] { check_targets(targets, kMeasured, ""); });
  EXPECT_NE(m.find(file.string() + ":2:"), std::string::npos) << m;
  EXPECT_NE(m.find("targets[0].name = fake.surface1.share_below_05um"), std::string::npos) << m;
  EXPECT_NE(m.find("did you mean 'fake.surface1.share_below_0.5um'"), std::string::npos) << m;
  EXPECT_NE(m.find("fake.surface1.test_samples"), std::string::npos) << m;  // its neighbours
}

TEST(Targets, TablesCheckPassesAndFailsWithExitCode) {
  testing::TempDir dir;
  const TableEntry& table = fake_table();
  TablesOptions options;
  options.configs_dir = dir.path();
  options.check = true;
  const fs::path manifest = dir / "studies/fake.yaml";
  // Both measured values on the passing side of their bound.
  write(manifest,
        "targets:\n"
        "  - {name: fake.surface1.share_below_0.5um, op: \">=\", value: 99.5, source: seed 000}\n"
        "  - {name: fake.surface1.test_samples, op: \"==\", value: 5940, source: paper}\n");
  std::ostringstream pass;
  EXPECT_EQ(tables_command(table.name, options, pass), 0);
  EXPECT_NE(pass.str().find("fake table"), std::string::npos);
  EXPECT_NE(pass.str().find("PASS"), std::string::npos) << pass.str();
  EXPECT_EQ(count(pass.str(), "FAIL"), 1u) << pass.str();  // "0 FAIL" only
  EXPECT_NE(pass.str().find("2 PASS, 0 FAIL"), std::string::npos) << pass.str();

  // A target beyond the measured value (99.71 < 99.8): FAIL and exit 1.
  write(manifest,
        "targets:\n"
        "  - {name: fake.surface1.share_below_0.5um, op: \">=\", value: 99.8, source: seed 000}\n"
        "  - {name: fake.surface1.test_samples, op: \"==\", value: 5940, source: paper}\n");
  std::ostringstream fail;
  EXPECT_EQ(tables_command(table.name, options, fail), 1);
  EXPECT_EQ(count(fail.str(), "FAIL"), 2u) << fail.str();  // the row and "1 FAIL"
  EXPECT_NE(fail.str().find("1 PASS, 1 FAIL"), std::string::npos) << fail.str();

  // Without --check the targets are not read.
  options.check = false;
  std::ostringstream plain;
  EXPECT_EQ(tables_command(table.name, options, plain), 0);
  EXPECT_EQ(plain.str().find("FAIL"), std::string::npos);
}

TEST(Targets, ProfileChecksOnlyItsDeclaredValues) {
  testing::TempDir dir;
  const TableEntry& table = fake_table();
  write(dir / "studies/fake.yaml",
        "targets:\n"
        "  - {name: fake.surface1.share_below_0.5um, op: \">=\", value: 99.9, source: seed 000}\n"
        "  - {name: fake.surface1.test_samples, op: \"==\", value: 5940, profiles: {quick: 5940}, "
        "source: paper}\n");
  TablesOptions options;
  options.configs_dir = dir.path();
  options.profile = "quick";
  std::ostringstream out;
  const TableCheck c = check_table(table, load_tables(table, options), options, out);
  EXPECT_EQ(c.passed, 1u);
  EXPECT_EQ(c.failed, 0u);  // 99.71 < 99.9 would fail, but not in the quick profile
  EXPECT_EQ(c.unchecked, 1u);
  EXPECT_NE(out.str().find("not checked"), std::string::npos) << out.str();
  options.profile = "";
  std::ostringstream full;
  EXPECT_EQ(check_table(table, load_tables(table, options), options, full).failed, 1u);
}

// A table with `load`: `tables --check` prints and measures from one load, and
// never calls the entry's own print or measure (which would load again).
TEST(Targets, CheckPrintsAndMeasuresFromOneLoad) {
  static int loads = 0;
  static const bool registered = [] {
    TableEntry e{"fake-load-once", "a table loaded once",
                 [](const TablesOptions&, std::ostream&) { ADD_FAILURE() << "print loaded again"; },
                 [](const TablesOptions&) {
                   ADD_FAILURE() << "measure loaded again";
                   return Measurements{};
                 },
                 "studies/fake.yaml"};
    e.load = [](const TablesOptions&) {
      ++loads;
      return LoadedTables{[](std::ostream& out) { out << "fake table, loaded once\n"; },
                          [] { return kMeasured; }};
    };
    register_table(e);
    return true;
  }();
  ASSERT_TRUE(registered);
  testing::TempDir dir;
  write(dir / "studies/fake.yaml",
        "targets:\n  - {name: fake.surface1.test_samples, op: \"==\", value: 5940, source: "
        "paper}\n");
  TablesOptions options;
  options.configs_dir = dir.path();
  options.check = true;
  std::ostringstream out;
  loads = 0;
  EXPECT_EQ(tables_command("fake-load-once", options, out), 0);
  EXPECT_EQ(loads, 1);
  EXPECT_NE(out.str().find("fake table, loaded once"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("1 PASS, 0 FAIL"), std::string::npos) << out.str();
}

TEST(Targets, AvailableTablesReportMalformedTargetsAsExit2) {
  testing::TempDir dir;
  fake_table();
  write(dir / "studies/fake.yaml",
        "targets:\n  - {name: fake.nothing, op: \">=\", value: 1, source: s}\n");
  TablesOptions options;
  options.configs_dir = dir.path();
  options.results_dir = dir / "results";  // no results: other tables are not printed
  options.check = true;
  std::ostringstream out;
  EXPECT_EQ(print_available_tables(options, out), 2);
  EXPECT_NE(out.str().find("targets of table fake-targets not checked"), std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("fake.nothing"), std::string::npos) << out.str();
}

}  // namespace
}  // namespace cnclab
