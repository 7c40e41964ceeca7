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
SweepExecution execute_sweep(const SweepPlan& plan, const std::filesystem::path& dir,
                             const SweepExecuteOptions& options, std::ostream* note);

}  // namespace cnclab
