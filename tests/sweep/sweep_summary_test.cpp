// Aggregation over repeats (mean and sample std by hand), ranking by the
// objective, and the summary file read back through h5 reads.
#include "cnclab/sweep/sweep_summary.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/io/h5.hpp"
#include "common/sweep_fixtures.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

constexpr double kTol = 1e-12;
using namespace sweep_fixtures;

TEST(SweepSummary, MeanAndSampleStdOverRepeatsAndRanking) {
  const SweepPlan plan = plan_of(false);
  const SweepSummary s = summarize(plan, outcomes());
  EXPECT_EQ(s.complete, 4u);
  EXPECT_EQ(s.failed, 1u);
  EXPECT_EQ(s.missing, 1u);
  ASSERT_EQ(s.points.size(), 3u);
  EXPECT_EQ(s.points[0].point, 1u);  // lowest mean rmse first
  EXPECT_NEAR(s.points[0].mean.at("rmse"), 1.25, kTol);
  EXPECT_NEAR(s.points[0].std.at("rmse"), std::sqrt(0.125), kTol);
  EXPECT_EQ(s.points[1].point, 0u);
  EXPECT_NEAR(s.points[1].mean.at("rmse"), 3.0, kTol);
  EXPECT_NEAR(s.points[1].std.at("rmse"), std::sqrt(2.0), kTol);
  EXPECT_NEAR(s.points[1].mean.at("mae"), 2.0, kTol);
  EXPECT_EQ(s.points[2].point, 2u);  // no results: last
  EXPECT_EQ(s.points[2].failed, 1u);
  EXPECT_EQ(s.best_trial, 2);  // rmse 1.0

  const SweepSummary max = summarize(plan_of(true), outcomes());
  EXPECT_EQ(max.points[0].point, 0u);
  EXPECT_EQ(max.points[2].point, 2u);  // still last when maximising
  EXPECT_EQ(max.best_trial, 1);        // rmse 4.0
}

// The case of a lucky seed: the best single trial (0.030) is a lucky repeat of the
// worse point (mean 4.83); the best trial must be a repeat of the best point.
TEST(SweepSummary, BestTrialIsOfTheBestPointNotTheBestSingleTrial) {
  const SweepPlan plan = plan_of(false);
  std::vector<TrialOutcome> o = {complete(0.030, 0), complete(9.63, 0),   // point 0: mean 4.83
                                 complete(0.065, 0), complete(0.060, 0),  // point 1: mean 0.0625
                                 TrialOutcome{},     TrialOutcome{}};
  const SweepSummary s = summarize(plan, o);
  ASSERT_EQ(s.points[0].point, 1u);
  // Two repeats ranked best first: 0.060 (trial 3), 0.065; (n - 1) / 2 = 0.
  EXPECT_EQ(s.best_trial, 3);
}

// Three complete repeats: the middle one by the objective, whatever the order.
TEST(SweepSummary, BestTrialIsTheMedianRepeat) {
  SweepPlan plan = plan_of(true);
  plan.repeats = 3;
  plan.trials.resize(3);
  for (std::size_t r = 0; r < 3; ++r) plan.trials[r].point = 0, plan.trials[r].repeat = r;
  const SweepSummary s = summarize(plan, {complete(3.0, 0), complete(1.0, 0), complete(2.0, 0)});
  EXPECT_EQ(s.best_trial, 2);  // rmse 2.0 of {3, 1, 2}
  // A failed repeat does not count: of {3, 1} maximised, (2 - 1) / 2 = 0 gives 3.0.
  const SweepSummary f = summarize(plan, {complete(3.0, 0), complete(1.0, 0), failed("x")});
  EXPECT_EQ(f.best_trial, 0);
}

TEST(SweepSummary, FileHoldsTheTableInPlanAndRankOrder) {
  testing::TempDir dir;
  const SweepPlan plan = plan_of(false);
  const auto o = outcomes();
  const SweepSummary s = summarize(plan, o);
  write_summary(dir / "summary.h5", plan, o, s);
  const H5File f = H5File::open_read(dir / "summary.h5");
  EXPECT_EQ(f.attribute_string("/", "format"), "cnclab-sweep-summary");
  EXPECT_EQ(f.attribute_int("/", "failed"), 1);
  EXPECT_EQ(f.attribute_int("/", "missing"), 1);
  EXPECT_EQ(f.attribute_string("/", "best_trial"), plan.trials[2].id);
  EXPECT_EQ(f.attribute_string("/", "best_trial_rule"),
            "median repeat of the rank-1 point by the objective");
  // Each ranked point names its trials (rank order: points 1, 0, 2).
  EXPECT_EQ(f.read_strings("/points/trials"),
            (std::vector<std::string>{plan.trials[2].id + "," + plan.trials[3].id,
                                      plan.trials[0].id + "," + plan.trials[1].id,
                                      plan.trials[4].id + "," + plan.trials[5].id}));
  EXPECT_EQ(f.read_strings("/trials/status"),
            (std::vector<std::string>{"complete", "complete", "complete", "complete", "failed",
                                      "missing"}));
  const auto rmse = f.read_vector("/trials/metrics/rmse");
  EXPECT_EQ(rmse[3], 1.5);
  EXPECT_TRUE(std::isnan(rmse[4]));
  EXPECT_EQ(f.read_vector("/trials/parameters/trainer.learning_rate")[2], 0.01);
  EXPECT_EQ(f.read_int64s("/points/point"), (std::vector<std::int64_t>{1, 0, 2}));
  EXPECT_NEAR(f.read_vector("/points/metrics/rmse/std")[1], std::sqrt(2.0), kTol);
}

// `cnclab show summary.h5` reads the summary back alone:
// the plan and every trial's outcome as written (warnings included), so
// summarize() gives the same ranking and best trial.
TEST(SweepSummary, ReadBackGivesThePlanOutcomesAndRanking) {
  testing::TempDir dir;
  const SweepPlan plan = plan_of(false);
  auto o = outcomes();
  o[1].warnings = {"constant predictions"};
  o[4].reason = "diverged at epoch 3";
  const SweepSummary s = summarize(plan, o);
  write_summary(dir / "summary.h5", plan, o, s);
  EXPECT_TRUE(is_sweep_summary(dir / "summary.h5"));
  const StoredSummary back = read_summary(dir / "summary.h5");
  EXPECT_EQ(back.plan.to_yaml(), plan.to_yaml());
  EXPECT_EQ(back.best_trial, plan.trials[2].id);
  ASSERT_EQ(back.outcomes.size(), o.size());
  for (std::size_t i = 0; i < o.size(); ++i) {
    EXPECT_EQ(back.outcomes[i].status, o[i].status) << i;
    EXPECT_EQ(back.outcomes[i].reason, o[i].reason) << i;
    EXPECT_EQ(back.outcomes[i].result_file, o[i].result_file) << i;
    EXPECT_EQ(back.outcomes[i].metrics, o[i].metrics) << i;
    EXPECT_EQ(back.outcomes[i].warnings, o[i].warnings) << i;
  }
  const SweepSummary again = summarize(back.plan, back.outcomes);
  EXPECT_EQ(again.best_trial, s.best_trial);
  ASSERT_EQ(again.points.size(), s.points.size());
  for (std::size_t p = 0; p < s.points.size(); ++p) {
    EXPECT_EQ(again.points[p].point, s.points[p].point);
  }
}

TEST(SweepSummary, SummariesWithoutWarningsStillReadAndResultsAreNotSummaries) {
  testing::TempDir dir;
  const SweepPlan plan = plan_of(false);
  const auto o = outcomes();
  write_summary(dir / "summary.h5", plan, o, summarize(plan, o));
  // As written before warnings existed.
  const hid_t old = H5Fopen((dir / "summary.h5").c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(old, "/trials/warnings", H5P_DEFAULT), 0);
  H5Fclose(old);
  const StoredSummary back = read_summary(dir / "summary.h5");
  for (const auto& t : back.outcomes) EXPECT_TRUE(t.warnings.empty());
  EXPECT_EQ(back.outcomes[3].metrics, o[3].metrics);
  {
    H5File f = H5File::create(dir / "other.h5");
    f.set_attribute("/", "format", "cnclab-result");
  }
  EXPECT_FALSE(is_sweep_summary(dir / "other.h5"));
  EXPECT_THROW(read_summary(dir / "other.h5"), IoError);
}

}  // namespace
}  // namespace cnclab

namespace cnclab {
namespace {

using namespace sweep_fixtures;

// A pruned trial (a model-based sweep's pruner stopped it) is done but never
// ranked, even when its numbers look better: its point ranks by its complete
// repeats only, and a point with only pruned trials ranks last.
TEST(SweepSummary, PrunedTrialsAreExcludedFromRankings) {
  const SweepPlan plan = plan_of(false);
  TrialOutcome pruned;
  pruned.status = TrialOutcome::Status::pruned;
  pruned.metrics = {{"rmse", 0.001}, {"mae", 0.001}};
  EXPECT_TRUE(pruned.done());
  // point 0: pruned + 3.0; point 1: 2.0 + 2.0; point 2: pruned only.
  const std::vector<TrialOutcome> o = {pruned,           complete(3.0, 0), complete(2.0, 0),
                                       complete(2.0, 0), pruned,           pruned};
  const SweepSummary s = summarize(plan, o);
  EXPECT_EQ(s.pruned, 3u);
  EXPECT_EQ(s.complete, 3u);
  ASSERT_EQ(s.points.size(), 3u);
  EXPECT_EQ(s.points[0].point, 1u);
  EXPECT_EQ(s.points[1].point, 0u);
  EXPECT_NEAR(s.points[1].mean.at("rmse"), 3.0, 1e-12);  // the pruned 0.001 left out
  EXPECT_EQ(s.points[2].point, 2u);
  EXPECT_EQ(s.points[2].pruned, 2u);
  EXPECT_EQ(s.best_trial, 2);
  EXPECT_EQ(to_string(TrialOutcome::Status::pruned), "pruned");
}

}  // namespace
}  // namespace cnclab
