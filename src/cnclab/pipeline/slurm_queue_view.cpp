#include "cnclab/pipeline/slurm_queue_view.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/sweep/slurm_tools.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {
namespace fs = std::filesystem;

SlurmQueueView slurm_queue_view(const fs::path& dir, bool strict) {
  SlurmQueueView v;
  v.submissions = read_submissions(dir);
  if (v.submissions.empty()) return v;
  try {
    v.states = squeue_tasks();
  } catch (const Error& e) {
    if (strict) throw;
    v.note = e.what();
    return v;
  }
  std::vector<std::string> jobs;
  for (const auto& s : v.submissions) jobs.push_back(s.array_job);
  std::string why;
  if (const auto ended = sacct_tasks(jobs, why)) {
    for (const auto& [task, state] : *ended) v.states.emplace(task, state);  // squeue first
  } else {
    v.note = why + " (tasks ended more than MinJobAge ago are not shown)";
  }
  return v;
}

std::string task_key(const SlurmSubmission& s, std::size_t task) {
  return s.array_job + "_" + std::to_string(task);
}

std::optional<SlurmPhase> trial_phase(
    const std::string& id, const SlurmQueueView& v,
    const std::map<std::string, std::vector<TrialPlacement>>& at) {
  const auto it = at.find(id);
  if (it == at.end()) return std::nullopt;
  std::optional<SlurmPhase> best;
  for (const auto& p : it->second) {
    const auto s = v.states.find(task_key(*p.submission, p.task));
    if (s == v.states.end()) continue;
    const SlurmPhase phase = slurm_phase(s->second);
    if (phase == SlurmPhase::running) return phase;
    if (phase == SlurmPhase::queued) best = phase;
  }
  return best;
}

SubmitSelection trials_to_submit(const SweepPlan& plan, const fs::path& dir,
                                 const SweepCommandOptions& o, const SlurmQueueView& v) {
  const auto outcomes = read_trial_outcomes(dir, plan);
  const auto placements = trial_placements(v.submissions);
  SubmitSelection sel;
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    const bool retry = o.retry_failed && outcomes[i].status == TrialOutcome::Status::failed;
    if (outcomes[i].done() && !retry) {
      ++sel.done;
    } else if (trial_phase(plan.trials[i].id, v, placements)) {
      ++sel.in_flight;
    } else {
      sel.ids.push_back(plan.trials[i].id);
    }
  }
  return sel;
}

EarlierJobs earlier_jobs(const SlurmQueueView& v) {
  EarlierJobs e;
  for (const auto& s : v.submissions) {
    for (std::size_t k = 0; k < s.tasks.size(); ++k) {
      const auto it = v.states.find(task_key(s, k));
      if (it != v.states.end() && slurm_phase(it->second) != SlurmPhase::ended) {
        e.arrays.push_back(s.array_job);
        break;
      }
    }
    if (!s.merge_job.empty()) e.merges.push_back(s.merge_job);
  }
  return e;
}

}  // namespace cnclab
