// The sweep table for people: mean ± std per point in rank order, failed
// trials, and the best trial with the rule that chose it.
#include "cnclab/report/sweep_report.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "common/sweep_fixtures.hpp"

namespace cnclab {
namespace {
using namespace sweep_fixtures;

// Issue 22's case: the best trial is the median repeat of the best point,
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

}  // namespace
}  // namespace cnclab
