// The sweeps under a results folder (found by their sweep.yaml) and the
// count of a sweep's trials by outcome, against hand-made folders and the
// sweep fixtures' outcomes.
#include "cnclab/pipeline/sweep_census.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "common/sweep_fixtures.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using namespace sweep_fixtures;

TEST(SweepCensus, FindsSweepFoldersSortedAndNotInsideASweep) {
  testing::TempDir dir;
  for (const char* sweep : {"b/lr", "a", "b/lr/trials/inner", "c/not_a_sweep"}) {
    fs::create_directories(dir / sweep);
  }
  for (const char* sweep : {"b/lr", "a", "b/lr/trials/inner"}) {
    std::ofstream(dir / (std::string(sweep) + "/sweep.yaml")) << "sweep: {}\n";
  }
  const auto found = sweep_folders(dir.path());
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0], dir / "a");
  EXPECT_EQ(found[1], dir / "b/lr");
  EXPECT_TRUE(sweep_folders(dir / "c").empty());
}

TEST(SweepCensus, CountsTrialsByOutcomeAndRunningByTheirLock) {
  const SweepPlan plan = plan_of(false);
  std::vector<TrialOutcome> o = outcomes();  // 4 complete, 1 failed, 1 without result
  o[3].status = TrialOutcome::Status::pruned;
  const std::set<std::string> held = {plan.trials[5].id};
  const TrialCensus c =
      count_trials(plan, o, [&](const std::string& id) { return held.contains(id); });
  EXPECT_EQ(c.complete, 3u);
  EXPECT_EQ(c.failed, 1u);
  EXPECT_EQ(c.running, 1u);         // trial 5: no result, its lock held
  EXPECT_EQ(c.without_result, 1u);  // trial 3: pruned, not running
  // In a sweep folder without locks nothing runs.
  testing::TempDir dir;
  const TrialCensus idle = count_trials(dir.path(), plan, o);
  EXPECT_EQ(idle.running, 0u);
  EXPECT_EQ(idle.without_result, 2u);
}

}  // namespace
}  // namespace cnclab
