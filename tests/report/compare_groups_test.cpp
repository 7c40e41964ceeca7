// `compare --group-by` (report/compare_groups.hpp) on in-memory runs:
// grouping by a key and by repeats, the statistics of the rows against
// scipy's numbers for the same data (welch_reference.py, case "unequal"),
// alpha marking, and the same columns in csv, json and md.
#include "cnclab/report/compare_groups.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

using testing::error_message;

ComparedRun run(const std::string& trainer, int seed, const std::string& hidden, double mse) {
  ComparedRun r;
  r.file = trainer + "-" + hidden + "-" + std::to_string(seed) + ".h5";
  r.record.experiment = "e";
  r.record.resolved_yaml = "name: e\nseed: " + std::to_string(seed) +
                           "\nmodel:\n  hidden: " + hidden + "\ntrainer:\n  type: " + trainer +
                           "\n";
  r.record.metrics = {{"mse", mse}, {"r2", 1 - mse / 10}};
  return r;
}

// welch_reference.py's "unequal" case: a = sgdm's five, b = lm's seven.
const std::vector<double> kA = {5.81, 6.02, 5.33, 6.44, 5.47};
const std::vector<double> kB = {6.58, 7.91, 5.12, 6.10, 7.40, 6.95, 5.88};
constexpr double kScipyP = 0.10161957739244924;  // ttest_ind(b, a, equal_var=False).pvalue
constexpr double kScipyT = 1.8238381497097349;
constexpr double kScipyTolerance = 1e-9;

std::vector<ComparedRun> two_trainers() {
  std::vector<ComparedRun> runs;
  for (std::size_t i = 0; i < kA.size(); ++i) {
    runs.push_back(run("sgdm", static_cast<int>(i), "[8]", kA[i]));
  }
  for (std::size_t i = 0; i < kB.size(); ++i) {
    runs.push_back(run("lm", static_cast<int>(i), "[8]", kB[i]));
  }
  return runs;
}

const GroupRow& row_of(const std::vector<GroupRow>& rows, const std::string& metric,
                       const std::string& group) {
  for (const auto& r : rows) {
    if (r.metric == metric && r.group == group) return r;
  }
  throw std::logic_error("no row " + metric + " " + group);
}

TEST(CompareGroups, ByKeyMatchesScipyAndMarksSignificance) {
  const auto runs = two_trainers();
  GroupCompareOptions o;
  o.group_by = "trainer.type";
  const auto groups = group_runs(runs, o.group_by);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].label, "trainer.type=sgdm");
  EXPECT_EQ(groups[1].label, "trainer.type=lm");
  const auto rows = compare_groups(runs, groups, o);
  ASSERT_EQ(rows.size(), 4u);  // mse and r2, two groups each
  const GroupRow& first = row_of(rows, "mse", "trainer.type=sgdm");
  EXPECT_TRUE(first.reference);
  EXPECT_EQ(first.summary.n, 5u);
  EXPECT_NEAR(first.summary.mean, (5.81 + 6.02 + 5.33 + 6.44 + 5.47) / 5, 1e-14);
  const GroupRow& lm = row_of(rows, "mse", "trainer.type=lm");
  EXPECT_NEAR(lm.welch.t, kScipyT, kScipyTolerance);
  EXPECT_NEAR(lm.welch.p_value, kScipyP, kScipyTolerance);
  EXPECT_EQ(lm.significant, "no");  // p = 0.10 >= 0.05
  EXPECT_LT(lm.bootstrap.low, lm.welch.difference);
  EXPECT_GT(lm.bootstrap.high, lm.welch.difference);
  // r2 = 1 - mse/10: the same test, same p.
  EXPECT_NEAR(row_of(rows, "r2", "trainer.type=lm").welch.p_value, kScipyP, kScipyTolerance);
  o.alpha = 0.2;  // p = 0.10 < 0.2
  EXPECT_EQ(row_of(compare_groups(runs, groups, o), "mse", "trainer.type=lm").significant, "yes");
}

TEST(CompareGroups, RepeatsGroupConfigsEqualApartFromSeed) {
  std::vector<ComparedRun> runs;
  for (int seed = 1; seed <= 3; ++seed) {
    runs.push_back(run("lm", seed, "[4]", 1.0 + seed));
    runs.push_back(run("lm", seed, "[8]", 0.5 + 0.1 * seed));
  }
  const auto groups = group_runs(runs, kGroupRepeats);
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].label, "model.hidden=[4]");  // trainer.type is the same everywhere
  EXPECT_EQ(groups[1].label, "model.hidden=[8]");
  EXPECT_EQ(groups[0].runs, (std::vector<std::size_t>{0, 2, 4}));
}

TEST(CompareGroups, NonFiniteValuesAreLeftOut) {
  auto runs = two_trainers();
  runs.back().record.metrics["mse"] = NAN;  // a diverged run
  GroupCompareOptions o;
  o.group_by = "trainer.type";
  const auto rows = compare_groups(runs, group_runs(runs, o.group_by), o);
  EXPECT_EQ(row_of(rows, "mse", "trainer.type=lm").summary.n, kB.size() - 1);
}

TEST(CompareGroups, BadKeysAreConfigErrors) {
  const auto runs = two_trainers();
  const std::string typo = error_message<ConfigError>([&] { group_runs(runs, "trainer.tpye"); });
  EXPECT_NE(typo.find("did you mean 'trainer.type'"), std::string::npos) << typo;
  const std::string one = error_message<ConfigError>([&] { group_runs(runs, "model.hidden"); });
  EXPECT_NE(one.find("one group"), std::string::npos) << one;
  GroupCompareOptions o;
  o.group_by = "trainer.type";
  o.alpha = 0.7;
  EXPECT_THROW(o.validate(), OptionError);
}

TEST(CompareGroups, FormatsCarryTheSameColumns) {
  const auto runs = two_trainers();
  GroupCompareOptions o;
  o.group_by = "trainer.type";
  std::ostringstream csv, json, md;
  print_group_comparison(runs, o, CompareFormat::csv, csv);
  print_group_comparison(runs, o, CompareFormat::json, json);
  print_group_comparison(runs, o, CompareFormat::markdown, md);
  const std::string header =
      "metric,group,n,mean,std,ci_low,ci_high,diff,welch_t,df,p_value,boot_low,boot_high,"
      "significant";
  EXPECT_EQ(csv.str().substr(0, csv.str().find('\n')), header);
  const auto doc = nlohmann::json::parse(json.str());
  ASSERT_EQ(doc["rows"].size(), 4u);
  std::string keys;
  for (const auto& [k, v] : doc["rows"][1].items()) keys += (keys.empty() ? "" : ",") + k;
  // nlohmann::json sorts keys; the csv header sorted the same way must match.
  std::vector<std::string> sorted;
  std::stringstream h(header);
  for (std::string c; std::getline(h, c, ',');) sorted.push_back(c);
  std::sort(sorted.begin(), sorted.end());
  std::string expected;
  for (const auto& c : sorted) expected += (expected.empty() ? "" : ",") + c;
  EXPECT_EQ(keys, expected);
  EXPECT_NEAR(doc["rows"][1]["p_value"].get<double>(), kScipyP, kScipyTolerance);
  EXPECT_TRUE(doc["rows"][0]["p_value"].is_null());  // the reference group
  EXPECT_EQ(doc["rows"][1]["significant"], "no");
  EXPECT_NE(md.str().find("| metric | group | n | mean |"), std::string::npos) << md.str();
}

}  // namespace
}  // namespace cnclab
