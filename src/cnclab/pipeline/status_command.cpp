#include "cnclab/pipeline/status_command.hpp"

#include <iomanip>
#include <map>

#include "cnclab/core/error.hpp"
#include "cnclab/io/lock_file.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/pipeline/slurm_queue_view.hpp"
#include "cnclab/pipeline/sweep_census.hpp"
#include "cnclab/sweep/slurm_queue.hpp"
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

int status_command(const fs::path& dir, std::ostream& out) {
  std::error_code ec;
  if (!fs::exists(dir / "sweep.yaml", ec)) return results_status_command(dir, out);
  const SweepPlan plan = load_plan(dir);
  const auto outcomes = read_trial_outcomes(dir, plan);
  const SlurmQueueView view = slurm_queue_view(dir, false);
  const auto placements = trial_placements(view.submissions);
  std::size_t complete = 0, failed = 0, running = 0, pending = 0, unqueued = 0, errors = 0;
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    const auto& r = outcomes[i];
    if (r.status == TrialOutcome::Status::complete) {
      ++complete;
    } else if (r.status == TrialOutcome::Status::failed) {
      ++failed;
    } else if (const auto phase = trial_phase(plan.trials[i].id, view, placements)) {
      ++(*phase == SlurmPhase::running ? running : pending);
    } else if (LockFile::held(trial_lock_path(dir, plan.trials[i].id))) {
      ++running;  // a process (a local sweep, a shard) runs it now
    } else {
      ++(r.status == TrialOutcome::Status::error ? errors : unqueued);
    }
  }
  out << "sweep " << dir.string() << " (" << plan.experiment << "): " << plan.trials.size()
      << " trials\n"
      << "  complete " << complete << ", failed " << failed << ", running " << running
      << ", pending " << pending << ", not queued " << unqueued + errors;
  if (errors) out << " (" << errors << " stopped with an error)";
  out << "\n";
  for (const auto& s : view.submissions) {
    std::map<std::string, std::size_t> states;
    for (std::size_t k = 0; k < s.tasks.size(); ++k) {
      const auto it = view.states.find(task_key(s, k));
      ++states[it == view.states.end() ? "unknown to Slurm" : it->second];
    }
    out << "  " << s.folder.filename().string() << ": array job " << s.array_job << ", tasks";
    for (const auto& [state, n] : states) out << " " << state << " " << n;
    if (!s.merge_job.empty()) out << "; merge job " << s.merge_job;
    out << "\n";
  }
  if (!view.note.empty()) out << "  note: " << view.note << "\n";
  const SweepSummary summary = summarize(plan, outcomes);
  if (summary.best_trial >= 0) {
    const auto& t = plan.trials[static_cast<std::size_t>(summary.best_trial)];
    const auto& r = outcomes[static_cast<std::size_t>(summary.best_trial)];
    out << "best so far: " << t.id << " (" << point_text(plan.keys, t.values)
        << "): " << plan.objective.metric << " "
        << format_metric(metric_or_nan(r.metrics, plan.objective.metric)) << "\n";
  } else {
    out << "best so far: none (no trial complete)\n";
  }
  if (unqueued + errors > 0 && !view.submissions.empty()) {
    out << "resubmit the trials not queued: the same `cnclab sweep ... --slurm` command\n";
  }
  return 0;
}

int reproduce_status_command(const fs::path& results_dir, std::ostream& out) {
  const ReproduceRecord record = read_reproduce_record(results_dir);
  SlurmTaskStates jobs;
  std::string note;
  try {
    jobs = squeue_jobs();
  } catch (const Error& e) {
    note = e.what();
  }
  out << "reproduce --slurm jobs of " << results_dir.string() << ": " << record.size() << "\n";
  for (const auto& [file, e] : record) {
    const auto state = jobs.find(e.job);
    std::error_code ec;
    // A result file, or a sweep folder with its summary.
    const bool made = !e.output.empty() && (fs::is_regular_file(e.output, ec) ||
                                            fs::exists(fs::path(e.output) / "summary.h5", ec));
    out << "  " << std::left << std::setw(28) << e.name << " job " << e.job << " "
        << (state == jobs.end() ? "(ended or unknown to Slurm)" : state->second)
        << (made ? ", output present" : "") << (e.array.empty() ? "" : "; array " + e.array)
        << "\n";
  }
  if (!note.empty()) out << "  note: " << note << "\n";
  return 0;
}

}  // namespace cnclab
