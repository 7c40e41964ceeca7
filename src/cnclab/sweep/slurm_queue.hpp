#pragma once
// The state of submitted array tasks, from squeue (jobs Slurm still holds,
// including those ended less than MinJobAge ago) and, where accounting is
// enabled, sacct (ended jobs). Many sites and the local test cluster run
// without accounting: sacct then fails, and only squeue's view is used.
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace cnclab {

// Slurm's state names (squeue %T, sacct State).
enum class SlurmPhase {
  queued,   // PENDING, REQUEUED, PREEMPTED (to be requeued), SUSPENDED, held, unknown names
  running,  // RUNNING, CONFIGURING, COMPLETING, SIGNALING, STAGE_OUT
  ended,    // COMPLETED, CANCELLED, FAILED, TIMEOUT, NODE_FAIL, OUT_OF_MEMORY, ...
};
// An unknown name counts as queued: a trial is never submitted twice because
// a state was not understood.
SlurmPhase slurm_phase(const std::string& state);

// Array tasks by "<array job id>_<task id>" -> state name.
using SlurmTaskStates = std::map<std::string, std::string>;

// The caller's array tasks Slurm still knows (squeue -h -r --me -t all -o
// '%F|%K|%T'). Error with squeue's message when it fails (no controller).
SlurmTaskStates squeue_tasks();

// The array tasks of `array_jobs` from sacct -n -P -X; nullopt when sacct is
// missing or fails (accounting disabled), with the reason in `why`.
std::optional<SlurmTaskStates> sacct_tasks(const std::vector<std::string>& array_jobs,
                                           std::string& why);

// The caller's single (non-array) jobs Slurm still knows, by job id -> state
// (the same squeue query; lines with task "N/A"). Error as squeue_tasks.
SlurmTaskStates squeue_jobs();

// Parsers of the two tools' output (exposed for tests).
SlurmTaskStates parse_squeue_tasks(const std::string& text);
SlurmTaskStates parse_squeue_jobs(const std::string& text);
SlurmTaskStates parse_sacct_tasks(const std::string& text);

}  // namespace cnclab
