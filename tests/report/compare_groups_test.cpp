// `compare --group-by` (report/compare_groups.hpp) on in-memory runs:
// grouping by a key and by repeats, strata of the keys that vary inside the
// groups and --pool, the statistics of the rows against scipy's numbers for
// the same data (welch_reference.py, case "unequal"; paired_reference.py,
// the strata), intervals within the metric's range, alpha marking, and the
// same columns in csv, json and md.
#include "cnclab/report/compare_groups.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
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

// The group's values of the row's metric, in run order.
std::vector<double> values_for(const std::vector<ComparedRun>& runs, const GroupRow& r) {
  std::vector<double> v;
  for (const auto& run : runs) {
    if (run.file.string().find(r.group.substr(r.group.find('=') + 1) + ";") != std::string::npos &&
        run.record.metrics.count(r.metric)) {
      v.push_back(run.record.metrics.at(r.metric));
    }
  }
  return v;
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
  const GroupDesign d = design_groups(runs, o);
  const auto& groups = d.groups;
  ASSERT_EQ(groups.size(), 2u);
  EXPECT_EQ(groups[0].label, "trainer.type=sgdm");
  EXPECT_EQ(groups[1].label, "trainer.type=lm");
  EXPECT_TRUE(d.varying.empty());  // only the seed differs inside the groups
  ASSERT_EQ(d.strata.size(), 1u);
  const auto rows = compare_groups(runs, d, o);
  ASSERT_EQ(rows.size(), 4u);  // mse and r2, two groups each
  const GroupRow& first = row_of(rows, "mse", "trainer.type=sgdm");
  EXPECT_TRUE(first.reference);
  EXPECT_EQ(first.summary.n, 5u);
  EXPECT_NEAR(first.summary.mean, (5.81 + 6.02 + 5.33 + 6.44 + 5.47) / 5, 1e-14);
  const GroupRow& lm = row_of(rows, "mse", "trainer.type=lm");
  EXPECT_NEAR(lm.welch.t, kScipyT, kScipyTolerance);
  EXPECT_NEAR(lm.welch.p_value, kScipyP, kScipyTolerance);
  EXPECT_EQ(lm.significant, "no");  // p = 0.10 >= 0.05
  // Seeds 0-4 in both groups pair up, but lm's seeds 5 and 6 do not: the
  // design is not paired, so Welch's test decides.
  EXPECT_EQ(lm.paired.pairs, 5u);
  EXPECT_EQ(lm.test, "welch");
  EXPECT_LT(lm.bootstrap.low, lm.welch.difference);
  EXPECT_GT(lm.bootstrap.high, lm.welch.difference);
  // r2 = 1 - mse/10: the same test, same p.
  EXPECT_NEAR(row_of(rows, "r2", "trainer.type=lm").welch.p_value, kScipyP, kScipyTolerance);
  o.alpha = 0.2;  // p = 0.10 < 0.2
  EXPECT_EQ(row_of(compare_groups(runs, d, o), "mse", "trainer.type=lm").significant, "yes");
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
  const auto rows = compare_groups(runs, design_groups(runs, o), o);
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
      "metric,stratum,group,n,mean,std,ci_low,ci_high,ci_clipped,diff,welch_t,welch_df,welch_p,"
      "boot_low,boot_high,pairs,paired_t,paired_p,wilcoxon_w,wilcoxon_p,test,significant";
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
  EXPECT_NEAR(doc["rows"][1]["welch_p"].get<double>(), kScipyP, kScipyTolerance);
  EXPECT_TRUE(doc["rows"][0]["welch_p"].is_null());  // the reference group
  EXPECT_EQ(doc["rows"][1]["pairs"], 5);
  EXPECT_EQ(doc["rows"][1]["significant"], "no");
  EXPECT_NE(md.str().find("| metric | stratum | group | n | mean |"), std::string::npos)
      << md.str();
}

// A run with the given config keys (dotted, flat) and metrics.
ComparedRun flat_run(const std::vector<std::pair<std::string, std::string>>& keys,
                     const std::map<std::string, double>& metrics) {
  ComparedRun r;
  std::string yaml = "name: e\n";
  for (const auto& [k, v] : keys) {
    std::string indent;
    std::string rest = k;
    for (auto dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.')) {
      yaml += indent + rest.substr(0, dot) + ":\n";
      indent += "  ";
      rest = rest.substr(dot + 1);
    }
    yaml += indent + rest + ": " + v + "\n";
    r.file += k + "=" + v + ";";
  }
  r.record.experiment = "e";
  r.record.resolved_yaml = yaml;
  r.record.metrics = metrics;
  return r;
}

// paired_reference.py's design: mse over seeds 1-4 for keep probability
// 0.5 and 1.0 (the grouping) x learning rate 0.001 and 0.01 (varying inside
// each group).
const std::map<std::pair<std::string, std::string>, std::vector<double>> kMse = {
    {{"0.5", "0.001"}, {2.10, 2.35, 1.98, 2.22}},
    {{"1.0", "0.001"}, {1.71, 2.05, 1.80, 1.77}},
    {{"0.5", "0.01"}, {0.91, 1.02, 0.88, 0.97}},
    {{"1.0", "0.01"}, {0.95, 1.01, 0.79, 0.99}},
};

std::vector<ComparedRun> dropout_by_learning_rate() {
  std::vector<ComparedRun> runs;
  for (const char* lr : {"0.001", "0.01"}) {
    for (const char* keep : {"0.5", "1.0"}) {
      const auto& mse = kMse.at({keep, lr});
      for (std::size_t s = 0; s < mse.size(); ++s) {
        // The keys in two sections, as a resolved config has them.
        runs.push_back(flat_run({{"seed", std::to_string(s + 1)},
                                 {"model.dropout.keep_probability", keep},
                                 {"trainer.learning_rate", lr}},
                                {{"mse", mse[s]}}));
      }
    }
  }
  return runs;
}

struct ScipyStratum {
  std::string learning_rate;
  double welch_t, welch_df, welch_p, paired_t, paired_p, wilcoxon_w, wilcoxon_p;
};

// paired_reference.py's output (scipy 1.10.1) for the strata.
const std::vector<ScipyStratum> kScipyStrata = {
    {"0.001", -3.0235174751190832, 5.9793535927667332, 0.023391272712512706, -5.6182931030077388,
     0.011148539632402379, 0, 0.125},
    {"0.01", -0.16984155512168955, 5.0360655737704922, 0.87174688788461596, -0.3499271061118831,
     0.74951879830369161, 5, 1},
};

// A learning rate varying inside the dropout groups: by default the groups
// are compared within each learning rate, and each stratum's numbers are
// scipy's for that stratum's runs.
TEST(CompareGroups, KeysVaryingInsideTheGroupsMakeStrata) {
  const auto runs = dropout_by_learning_rate();
  GroupCompareOptions o;
  o.group_by = "model.dropout.keep_probability";
  const GroupDesign d = design_groups(runs, o);
  EXPECT_EQ(d.varying, std::vector<std::string>{"trainer.learning_rate"});
  EXPECT_FALSE(d.pooled);
  ASSERT_EQ(d.strata.size(), 2u);
  const auto rows = compare_groups(runs, d, o);
  ASSERT_EQ(rows.size(), 4u);  // 2 strata x 2 groups
  for (const auto& s : kScipyStrata) {
    const std::string stratum = "trainer.learning_rate=" + s.learning_rate;
    const GroupRow* row = nullptr;
    for (const auto& r : rows) {
      if (r.stratum == stratum && r.group == "model.dropout.keep_probability=1.0") row = &r;
    }
    ASSERT_NE(row, nullptr) << stratum;
    EXPECT_EQ(row->summary.n, 4u);
    EXPECT_NEAR(row->welch.t, s.welch_t, kScipyTolerance) << stratum;
    EXPECT_NEAR(row->welch.df, s.welch_df, kScipyTolerance) << stratum;
    EXPECT_NEAR(row->welch.p_value, s.welch_p, kScipyTolerance) << stratum;
    EXPECT_EQ(row->paired.pairs, 4u);  // seeds 1-4 in both groups
    EXPECT_NEAR(row->paired.t, s.paired_t, kScipyTolerance) << stratum;
    EXPECT_NEAR(row->paired.p_value, s.paired_p, kScipyTolerance) << stratum;
    EXPECT_EQ(row->wilcoxon.w, s.wilcoxon_w) << stratum;
    EXPECT_NEAR(row->wilcoxon.p_value, s.wilcoxon_p, kScipyTolerance) << stratum;
    EXPECT_EQ(row->test, "paired t");  // every run has its pair
  }
  EXPECT_EQ(row_of(rows, "mse", "model.dropout.keep_probability=1.0").significant, "yes");

  // --pool: one comparison across the learning rates, said so; pairs by
  // seed and learning rate.
  o.pool = true;
  const GroupDesign pooled = design_groups(runs, o);
  EXPECT_TRUE(pooled.pooled);
  ASSERT_EQ(pooled.strata.size(), 1u);
  const auto prow = compare_groups(runs, pooled, o)[1];
  EXPECT_EQ(prow.summary.n, 8u);
  EXPECT_NEAR(prow.welch.t, -0.5830844711185007, kScipyTolerance);
  EXPECT_NEAR(prow.welch.p_value, 0.56983903000390967, kScipyTolerance);
  EXPECT_EQ(prow.paired.pairs, 8u);
  EXPECT_NEAR(prow.paired.t, -2.5143339078173366, kScipyTolerance);
  EXPECT_NEAR(prow.paired.p_value, 0.040141699433739672, kScipyTolerance);
  std::ostringstream text;
  print_group_comparison(runs, o, CompareFormat::table, text);
  EXPECT_NE(text.str().find("POOLED over trainer.learning_rate"), std::string::npos) << text.str();
  o.pool = false;
  std::ostringstream strata;
  print_group_comparison(runs, o, CompareFormat::table, strata);
  EXPECT_NE(strata.str().find("stratum 2: trainer.learning_rate=0.01 (2 group(s), 8 run(s))"),
            std::string::npos)
      << strata.str();
}

// Keys constant in each group that differ between the groups (an lm has no
// learning rate, an sgdm no mu) go with the grouping: no strata, named.
TEST(CompareGroups, KeysThatGoWithTheGroupsAreNamedNotStratified) {
  std::vector<ComparedRun> runs;
  for (int seed = 1; seed <= 3; ++seed) {
    runs.push_back(flat_run({{"seed", std::to_string(seed)},
                             {"trainer.type", "sgdm"},
                             {"trainer.learning_rate", "0.01"}},
                            {{"mse", 1.0 + 0.1 * seed}}));
    runs.push_back(
        flat_run({{"seed", std::to_string(seed)}, {"trainer.type", "lm"}, {"trainer.mu", "0.001"}},
                 {{"mse", 0.8 + 0.05 * seed * seed}}));
  }
  GroupCompareOptions o;
  o.group_by = "trainer.type";
  const GroupDesign d = design_groups(runs, o);
  EXPECT_TRUE(d.varying.empty());
  EXPECT_EQ(d.with_groups, (std::vector<std::string>{"trainer.learning_rate", "trainer.mu"}));
  ASSERT_EQ(d.strata.size(), 1u);
  EXPECT_EQ(d.strata[0].groups.size(), 2u);
}

// Student-t intervals that would leave a metric's possible range are
// clipped to it (r2 <= 1, errors >= 0) and say so.
TEST(CompareGroups, IntervalsStayWithinTheMetricsRange) {
  const std::vector<double> r2 = {0.99, 0.95, 0.999, 0.90}, mae = {0.01, 0.2, 0.02, 0.05};
  std::vector<ComparedRun> runs;
  for (std::size_t s = 0; s < r2.size(); ++s) {
    for (const char* type : {"sgdm", "lm"}) {
      const double shift = std::string(type) == "lm" ? 0.001 : 0.0;
      runs.push_back(flat_run({{"seed", std::to_string(s)}, {"trainer.type", type}},
                              {{"r2", r2[s] - shift},
                               {"validation.r2", r2[s]},
                               {"mae", mae[s] + shift},
                               {"contour_rms", mae[s]}}));
    }
  }
  GroupCompareOptions o;
  o.group_by = "trainer.type";
  const auto rows = compare_groups(runs, design_groups(runs, o), o);
  for (const auto& r : rows) {
    // The unclipped Student-t interval, for comparison.
    const SampleSummary raw = summarize(r.metric.ends_with("r2") ? r2 : mae);
    if (r.metric.ends_with("r2")) {
      if (r.group == "trainer.type=sgdm") {
        ASSERT_GT(raw.ci_high, 1.0);  // the case to clip
      }
      EXPECT_LE(r.summary.ci_high, 1.0) << r.metric;
      EXPECT_EQ(r.ci_clipped, "high") << r.metric << " " << r.group;
      EXPECT_EQ(r.summary.ci_low, summarize(values_for(runs, r)).ci_low);  // below: unchanged
    } else if (r.metric == "mae") {
      EXPECT_GE(r.summary.ci_low, 0.0);
      EXPECT_EQ(r.ci_clipped, "low");
    } else {
      // contour_rms: a study's metric; this library registers no range for
      // it (report_tests links no study), so its interval is not clipped.
      EXPECT_LT(r.summary.ci_low, 0.0);
      EXPECT_EQ(r.ci_clipped, "");
    }
  }
  std::ostringstream text;
  print_group_comparison(runs, o, CompareFormat::table, text);
  EXPECT_NE(text.str().find("clipped to the metric's possible range"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
