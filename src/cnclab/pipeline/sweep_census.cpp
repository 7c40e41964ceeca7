#include "cnclab/pipeline/sweep_census.hpp"

#include <algorithm>

#include "cnclab/io/lock_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;

std::vector<fs::path> sweep_folders(const fs::path& dir) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec);
       it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (!it->is_directory(ec)) continue;
    if (fs::exists(it->path() / "sweep.yaml", ec)) {
      found.push_back(it->path());
      it.disable_recursion_pending();
    }
  }
  std::sort(found.begin(), found.end());
  return found;
}

TrialCensus count_trials(const SweepPlan& plan, const std::vector<TrialOutcome>& outcomes,
                         const std::function<bool(const std::string& id)>& running) {
  TrialCensus c;
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    const auto status = outcomes[i].status;
    if (status == TrialOutcome::Status::complete) {
      ++c.complete;
    } else if (status == TrialOutcome::Status::failed) {
      ++c.failed;
    } else if (running(plan.trials[i].id)) {
      ++c.running;
    } else {
      ++c.without_result;
    }
  }
  return c;
}

TrialCensus count_trials(const fs::path& dir, const SweepPlan& plan,
                         const std::vector<TrialOutcome>& outcomes) {
  return count_trials(plan, outcomes, [&](const std::string& id) {
    return LockFile::held(trial_lock_path(dir, id));
  });
}

}  // namespace cnclab
