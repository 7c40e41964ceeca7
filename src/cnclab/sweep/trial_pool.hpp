#pragma once
// Runs sweep trials in parallel, each in its own forked child process:
// single-threaded, isolated (a crash, an abort or an out-of-memory kill ends
// that trial only) and bit-identical to running the trial alone, because a
// trial's numbers depend only on its resolved config.
//
// Interruption: SIGINT and SIGTERM are received synchronously by the pool
// (blocked and waited for with sigtimedwait, so no handler and no global
// flag); the pool forwards SIGTERM to the running trials, waits for them and
// reports the signal. Their temporaries are partial files (never read as
// results), so a re-run resumes with nothing lost or duplicated. SIGUSR1
// (Slurm's warning before a time limit or pre-emption, slurm_script.hpp)
// drains the pool instead: no trial starts, the running ones finish, and the
// pool reports SIGUSR1. Children die
// with the parent (PR_SET_PDEATHSIG), so `kill -9` of the sweep leaves no
// trial running.
//
// Timeout: a trial running longer than PoolOptions::trial_timeout_seconds is
// killed (SIGKILL) and ends as an error whose note starts with "timeout:"
// (kTimeoutNote), which the sweep records as a failed trial.
#include <cstddef>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/experiment/runner.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {

struct TrialJob {
  std::size_t index = 0;  // the caller's number for it, passed back to on_done
  const LoadedExperiment* experiment = nullptr;
  std::filesystem::path result_file;  // where the trial's result goes
  std::filesystem::path error_file;   // written when the trial stops without a result
  // Other work run in the child instead of an experiment (e.g. generating a
  // dataset into the cache while trainings run); its exceptions end it like
  // a trial's. Set either this or `experiment`.
  std::function<void()> task;
  // false: PoolOptions::trial_timeout_seconds does not apply (a task that
  // waits for another process, which takes as long as that process does).
  bool timed = true;
};

// How a child ended.
struct TrialExit {
  enum class Kind { result, error, interrupted } kind = Kind::result;
  std::string message;        // error: the exception text or the signal that killed it
  bool config_error = false;  // error: the run threw a ConfigError (its text is in error_file)
  bool timeout = false;       // error: killed after the trial timeout
};

// The start of a timed-out trial's error note.
inline constexpr const char* kTimeoutNote = "timeout:";

struct PoolOptions {
  std::size_t jobs = 1;  // trials at once (>= 1)
  RunOptions run;        // results_dir, datasets_dir; result_file is set per trial
  // false: trials run silently (run.log and run.progress are ignored), as
  // parallel trials' output would interleave; true: they write to run.log.
  bool trial_output = false;
  // Called in the parent about once a second while trials run (progress).
  std::function<void()> on_tick;
  // Kill a trial still running after this many seconds; 0 = no limit. The
  // pool checks about once a second.
  double trial_timeout_seconds = 0;
};

// Cores this process may run on (the affinity mask: what Slurm or taskset
// grants), at least 1: the default number of parallel trials.
std::size_t available_cores();

// Runs `jobs` and calls `on_done` in the parent as each trial ends, with the
// job's position in `jobs`. Returns 0 when all ran, or the number of the
// signal (SIGINT, SIGTERM, or SIGUSR1: drained) that stopped the
// sweep early; trials not started then are simply not run.
int run_trial_pool(const std::vector<TrialJob>& jobs, const PoolOptions& options,
                   const std::function<void(std::size_t job, const TrialExit&)>& on_done);

// Jobs that become ready as others end (a dependency graph): whenever a slot
// is free the pool asks `next_ready` for a job that can start now, nullopt
// when none can yet; `on_done` (called with the job's `index`) may make more
// ready. Ends when nothing runs and `next_ready` has nothing; returns as above.
int run_trial_pool(const std::function<std::optional<TrialJob>()>& next_ready,
                   const PoolOptions& options,
                   const std::function<void(std::size_t index, const TrialExit&)>& on_done);

}  // namespace cnclab
