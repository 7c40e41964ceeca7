#pragma once
// Running a sweep's trials: what `cnclab sweep` (src/cli) and a `kind:
// sweep` job (sweep_job.hpp) share.
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {

struct SweepExecuteOptions {
  CommandOptions common;  // results and datasets folders; regenerate; quiet is not read
  std::size_t jobs = 0;   // trials at once; 0 = the cores this process may use (affinity)
  std::size_t shard = 1, shards = 1;  // run trials of shard `shard` (1-based) of `shards`
  bool rerun = false;                 // run every trial of the shard, even those with a result
  bool retry_failed = false;          // run failed trials (failed status, timeout) again
  double trial_timeout = 0;           // seconds; a trial still running is killed; 0 = none
  // Non-empty: run only these trials of the shard (ids as in sweep.yaml; a
  // Slurm array task's list, slurm_script.hpp). ConfigError on an unknown id.
  std::vector<std::string> trial_ids;
};

struct SweepExecution {
  std::vector<TrialOutcome> outcomes;  // every trial of the plan, after the run
  std::vector<std::size_t> mine;       // the shard's trials (plan indices)
  std::size_t ran = 0;                 // trials started now
  std::size_t finished = 0;            // of those, how many ended (not interrupted)
  int stopped = 0;                     // the signal that interrupted the sweep; 0: none
};

// Runs the shard's trials of `plan` that have no result in `dir` yet (a
// stored plan, store_plan), in parallel (trial_pool.hpp); trials whose
// upstream results changed run again. One line per finished trial to `note`
// (nullptr: silent). What `cnclab sweep` and a `kind: sweep` job do.
//
// One writer per trial: several processes may work on one sweep folder at
// once (shards, Slurm array tasks, a second `cnclab sweep` of the same plan,
// `reproduce` jobs). Before a trial starts, or takes the result store's file,
// the process takes the trial's lock file trials/.<id>.lock (io/lock_file.hpp:
// O_EXCL, NFS-safe, naming host and pid, as the dataset cache's). A trial
// whose lock another process holds is left to it; once this process has
// nothing else to run it waits for those trials (a note names the lock file
// and its holder) and then takes each one's outcome, or runs it if the holder
// stopped without one. With the lock held, a trial whose files another process
// wrote since this one looked is not run again (even with --rerun): each
// trial is trained once, and its result file, once linked to the result
// store, is never replaced by a second training (which would cut the link).
// Processes of different hosts coordinate only through the shared folder: a
// lock of a crashed node stays until removed (the note says which file).
SweepExecution execute_sweep(const SweepPlan& plan, const std::filesystem::path& dir,
                             const SweepExecuteOptions& options, std::ostream* note);

}  // namespace cnclab
