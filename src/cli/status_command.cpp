// `cnclab status RESULTS_DIR`: a results folder (not a sweep folder) lists
// the jobs `reproduce --slurm` submitted into it and every sweep folder below
// it, one line each (slurm_command.hpp, status_command).
#include <filesystem>
#include <ostream>

#include "cli/reproduce_slurm.hpp"
#include "cli/slurm_command.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/pipeline/sweep_census.hpp"
#include "cnclab/sweep/slurm_reproduce_record.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

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
  const TrialCensus c = count_trials(dir, plan, outcomes);
  out << " (" << plan.experiment << "): " << plan.trials.size() << " trials, " << c.complete
      << " complete, " << c.failed << " failed, " << c.running << " running, " << c.without_result
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
