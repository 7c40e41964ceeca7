#pragma once
// The sweeps under a results folder and how far each has got, for
// `cnclab status RESULTS_DIR` (one line per sweep folder).
#include <cstddef>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {

// Sweep folders (holding sweep.yaml) below `dir`, sorted; a sweep folder's
// own subfolders are not searched.
std::vector<std::filesystem::path> sweep_folders(const std::filesystem::path& dir);

// A sweep's trials by outcome: complete, failed, and of the others (no
// result, or one neither complete nor failed) those a process is running
// and those without a result.
struct TrialCensus {
  std::size_t complete = 0;
  std::size_t failed = 0;
  std::size_t running = 0;
  std::size_t without_result = 0;
};
// `running(id)`: whether trial `id` is being run now.
TrialCensus count_trials(const SweepPlan& plan, const std::vector<TrialOutcome>& outcomes,
                         const std::function<bool(const std::string& id)>& running);
// Running: a process holds the trial's lock in sweep folder `dir`
// (trial_lock_path, sweep_plan.hpp).
TrialCensus count_trials(const std::filesystem::path& dir, const SweepPlan& plan,
                         const std::vector<TrialOutcome>& outcomes);

}  // namespace cnclab
