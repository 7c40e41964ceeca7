// `cnclab status RESULTS_DIR`: a results folder (not a sweep folder) lists
// the jobs `reproduce --slurm` submitted into it and every sweep folder below
// it, one line each (slurm_command.hpp, status_command).
#include <algorithm>
#include <filesystem>
#include <ostream>

#include "cli/reproduce_slurm.hpp"
#include "cli/slurm_command.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/io/lock_file.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/sweep/slurm_reproduce_record.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// Sweep folders (holding sweep.yaml) below `dir`, sorted; a sweep folder's
// own subfolders are not searched.
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

// "  DIR (experiment): 12 trials, 10 complete, 1 failed, 1 running here, 0 without result; best
// ..."
void sweep_line(const fs::path& dir, std::ostream& out) {
  out << "  " << dir.string();
  SweepPlan plan;
  try {
    plan = load_plan(dir);
  } catch (const Error& e) {
    out << ": unreadable (" << e.what() << ")\n";
    return;
  }
  const auto outcomes = read_trial_outcomes(dir, plan);
  std::size_t complete = 0, failed = 0, running = 0, none = 0;
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    const auto status = outcomes[i].status;
    if (status == TrialOutcome::Status::complete) {
      ++complete;
    } else if (status == TrialOutcome::Status::failed) {
      ++failed;
    } else if (LockFile::held(trial_lock_path(dir, plan.trials[i].id))) {
      ++running;
    } else {
      ++none;
    }
  }
  out << " (" << plan.experiment << "): " << plan.trials.size() << " trials, " << complete
      << " complete, " << failed << " failed, " << running << " running, " << none
      << " without result";
  const SweepSummary summary = summarize(plan, outcomes);
  if (summary.best_trial >= 0) {
    const auto b = static_cast<std::size_t>(summary.best_trial);
    out << "; best " << plan.trials[b].id << ": " << plan.objective.metric << " "
        << format_metric(metric_or_nan(outcomes[b].metrics, plan.objective.metric));
  }
  std::error_code ec;
  if (fs::is_directory(dir / "slurm", ec)) out << "; Slurm tasks: cnclab status " << dir.string();
  out << "\n";
}

}  // namespace

int results_status_command(const fs::path& dir, std::ostream& out) {
  std::error_code ec;
  const bool jobs = fs::exists(reproduce_slurm_dir(dir) / "jobs.yaml", ec);
  if (jobs) reproduce_status_command(dir, out);
  const std::vector<fs::path> sweeps = sweep_folders(dir);
  if (!jobs && sweeps.empty()) {
    throw ConfigError(dir.string() +
                      ": no sweep folder (sweep.yaml) and no `reproduce --slurm` jobs in or below "
                      "it; `cnclab status` takes a sweep folder or a results folder");
  }
  if (!sweeps.empty()) {
    out << "sweeps under " << dir.string() << ": " << sweeps.size()
        << " (running: a process holds the trial; `cnclab status SWEEP_DIR` for details)\n";
  }
  for (const auto& s : sweeps) sweep_line(s, out);
  return 0;
}

}  // namespace cnclab
