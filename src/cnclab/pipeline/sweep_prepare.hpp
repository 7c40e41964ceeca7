#pragma once
// `cnclab sweep`'s options, and a sweep planned with its folder chosen from a
// file and the command line's words (what `cnclab sweep` runs, `sweep --slurm`
// and `reproduce --slurm` submit: slurm_sweep_submit.hpp, reproduce_slurm.hpp).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/sweep/model_search.hpp"
#include "cnclab/sweep/sweep_execute.hpp"
#include "cnclab/sweep/sweep_plan.hpp"

namespace cnclab {

struct SweepCommandOptions {
  CommandOptions common;      // regenerate: each dataset the trials need once
  std::size_t jobs = 0;       // trials at once; 0 = the cores this process may use (affinity)
  std::string shard;          // "K/N" or "" for all trials
  std::filesystem::path dir;  // sweep folder; "" = <results>/<name>/sweep-<plan hash>
  bool regenerate = false;    // regenerate the datasets the trials need once
  double trial_timeout = 0;   // seconds; a trial running longer is killed, failed "timeout"
  bool retry_failed = false;  // run failed trials (failed status, timeout) again
  bool rerun = false;         // run every trial again, also those with a result (or a stored one)
  // Command-line settings of the sweep block (override the YAML's).
  std::optional<std::size_t> repeats, trials;
  std::optional<std::string> method, objective;
  std::optional<std::uint64_t> sweep_seed;
  std::vector<std::string> trial_ids;  // run only these trials (a Slurm array task's list)
};

// A sweep planned and its folder chosen: what `cnclab sweep` runs and
// `cnclab sweep --slurm` submits (slurm_sweep_submit.hpp).
struct PreparedSweep {
  SweepPlan plan;
  std::filesystem::path dir;
  SweepExecuteOptions exec;  // jobs (the kind: sweep file's if not given), shard, ...
  std::string name;          // a kind: sweep file's name; "": the swept experiment's
  SweepSpec spec;            // the resolved sweep block
  SearchSource source;       // what the trials are made from (model-based methods)
};
PreparedSweep prepare_sweep(const std::filesystem::path& experiment,
                            const std::vector<std::string>& words,
                            std::optional<std::uint64_t> seed, const SweepCommandOptions& options);

}  // namespace cnclab
