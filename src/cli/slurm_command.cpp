#include "cli/slurm_command.hpp"

#include <map>

#include "cnclab/core/error.hpp"
#include "cnclab/io/lock_file.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/pipeline/slurm_queue_view.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {
namespace fs = std::filesystem;

int slurm_sweep_command(const fs::path& experiment, const std::vector<std::string>& words,
                        std::optional<std::uint64_t> seed, const SweepCommandOptions& o,
                        const SlurmOptions& slurm, std::ostream& out, std::ostream& log) {
  slurm.validate();
  if (!o.shard.empty()) throw ConfigError("--shard with --slurm: the array tasks are the shards");
  if (o.jobs != 0) {
    throw ConfigError("--jobs with --slurm: a task runs --cpus-per-task trials at once");
  }
  if (!o.trial_ids.empty()) throw ConfigError("--trial-ids with --slurm: the tasks set it");
  if (o.rerun) {
    throw ConfigError(
        "--rerun with --slurm: an array gets only the trials without a result; train them "
        "again with `cnclab sweep ... --rerun` (one job, or --shard K/N per job)");
  }
  if (!slurm.dry_run) check_slurm_clients();
  const SweepSlurmResult r = submit_sweep_slurm(experiment, words, seed, o, slurm, {}, out, log);
  return r.final_rejected ? 1 : 0;
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

}  // namespace cnclab
