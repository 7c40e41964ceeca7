// The sweep table for people: mean ± std per point in rank order, failed
// trials, and the best trial with the rule that chose it.
#include "cnclab/report/sweep_report.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "common/sweep_fixtures.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {
using namespace sweep_fixtures;

// The case of a lucky seed: the best trial is the median repeat of the best point,
// and its line names the rule.
TEST(SweepReport, BestTrialLineNamesTheRule) {
  const SweepPlan plan = plan_of(false);
  const std::vector<TrialOutcome> o = {complete(0.030, 0), complete(9.63, 0), complete(0.065, 0),
                                       complete(0.060, 0), TrialOutcome{},    TrialOutcome{}};
  std::ostringstream table;
  print_summary(table, plan, o, summarize(plan, o), "sweep");
  EXPECT_NE(table.str().find("rmse 0.06 (median repeat of the rank-1 point by the objective, 2 "
                             "complete)"),
            std::string::npos)
      << table.str();
}

TEST(SweepReport, RankedMeanStdAndFailedTrials) {
  const SweepPlan plan = plan_of(false);
  const auto o = outcomes();
  std::ostringstream table;
  print_summary(table, plan, o, summarize(plan, o), "sweep");
  const std::string text = table.str();
  EXPECT_NE(text.find("1.25 ± 0.353553"), std::string::npos) << text;
  EXPECT_NE(text.find("FAILED trial"), std::string::npos) << text;
  EXPECT_LT(text.find("0.01 "), text.find("0.1 ")) << text;  // ranked
}

// A complete trial with a warning is counted in its point's
// row and listed under the table; the best trial's line carries its warning.
TEST(SweepReport, WarnedTrialsAreMarkedAndListed) {
  const SweepPlan plan = plan_of(false);
  auto o = outcomes();
  o[2].warnings = {"constant predictions"};  // point 1 (rank 1), repeat 0
  std::ostringstream table;
  print_summary(table, plan, o, summarize(plan, o), "sweep");
  const std::string text = table.str();
  EXPECT_NE(text.find("2/2, 1 warning"), std::string::npos) << text;
  EXPECT_NE(text.find("WARNING trial " + plan.trials[2].id +
                      " (trainer.learning_rate=0.01, repeat 0): constant predictions"),
            std::string::npos)
      << text;
  // Best trial: of point 1's repeats (rmse 1.0 and 1.5) the better one, trial 2.
  EXPECT_NE(text.find("complete); warning: constant predictions\n"), std::string::npos) << text;
}

// `cnclab show summary.h5` prints, from the file alone, what `sweep merge`
// printed from the trials.
TEST(SweepReport, StoredSummaryPrintsTheSameTable) {
  testing::TempDir dir;
  const SweepPlan plan = plan_of(false);
  auto o = outcomes();
  o[1].warnings = {"constant predictions"};
  const SweepSummary s = summarize(plan, o);
  write_summary(dir / "summary.h5", plan, o, s);
  std::ostringstream merged, shown;
  print_summary(merged, plan, o, s, dir.path());
  const StoredSummary back = read_summary(dir / "summary.h5");
  print_summary(shown, back.plan, back.outcomes, summarize(back.plan, back.outcomes), dir.path());
  EXPECT_EQ(shown.str(), merged.str());
  std::ostringstream stored;  // what `cnclab show` prints: the same, no note
  print_stored_summary(dir / "summary.h5", stored);
  EXPECT_EQ(stored.str(), merged.str());
}

}  // namespace
}  // namespace cnclab
