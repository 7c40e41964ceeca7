#pragma once
// A sweep's Slurm array tasks as Slurm sees them now (squeue, then sacct for
// the tasks that ended), and what follows from that view: a trial's phase,
// the trials still to submit, the earlier arrays and merge jobs in flight.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/pipeline/sweep_prepare.hpp"
#include "cnclab/sweep/slurm_queue.hpp"
#include "cnclab/sweep/slurm_submission.hpp"

namespace cnclab {

// The array tasks of a sweep's submissions as Slurm sees them now.
struct SlurmQueueView {
  std::vector<SlurmSubmission> submissions;
  SlurmTaskStates states;  // "<array job>_<task>" -> state; absent: Slurm has forgotten it
  std::string note;        // what the view lacks (squeue or sacct unavailable)
};

// `strict`: a failing squeue is an error (a submission must not guess what
// is in flight); else it is noted and the view has no states.
SlurmQueueView slurm_queue_view(const std::filesystem::path& dir, bool strict);

// "<array job>_<task>": a task's key in SlurmQueueView::states.
std::string task_key(const SlurmSubmission& s, std::size_t task);

// The trial's most active array task: running before queued; nullopt when
// none is queued or running (ended, forgotten, or never submitted).
std::optional<SlurmPhase> trial_phase(const std::string& id, const SlurmQueueView& v,
                                      const std::map<std::string, std::vector<TrialPlacement>>& at);

// The trials to submit: no result yet (failed too with --retry-failed) and
// not held by a queued or running array task. Counts what it skipped.
struct SubmitSelection {
  std::vector<std::string> ids;
  std::size_t done = 0, in_flight = 0;
};
SubmitSelection trials_to_submit(const SweepPlan& plan, const std::filesystem::path& dir,
                                 const SweepCommandOptions& o, const SlurmQueueView& v);

// Arrays of earlier submissions with tasks still queued or running, and
// their merge jobs still waiting: the new merge job waits for all those
// arrays and replaces those merge jobs, so the last summary.h5 written is
// the one made after every array ended.
struct EarlierJobs {
  std::vector<std::string> arrays, merges;
};
EarlierJobs earlier_jobs(const SlurmQueueView& v);

}  // namespace cnclab
