#pragma once
// `cnclab sweep` and `cnclab sweep merge` as library functions (exit codes as
// in commands.hpp; an interrupted sweep returns 128 + the signal number).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/sweep/sweep_execute.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

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
// `cnclab sweep --slurm` submits (slurm_command.hpp).
struct PreparedSweep {
  SweepPlan plan;
  std::filesystem::path dir;
  SweepExecuteOptions exec;  // jobs (the kind: sweep file's if not given), shard, ...
  std::string name;          // a kind: sweep file's name; "": the swept experiment's
};
PreparedSweep prepare_sweep(const std::filesystem::path& experiment,
                            const std::vector<std::string>& words,
                            std::optional<std::uint64_t> seed, const SweepCommandOptions& options);

// `words`: key=value overrides and key=v1,v2 / key=fn(...) sweep parameters.
int sweep_command(const std::filesystem::path& experiment, const std::vector<std::string>& words,
                  std::optional<std::uint64_t> seed, const SweepCommandOptions& options,
                  std::ostream& out, std::ostream& log);

// Builds summary.h5 of a sweep folder from the trial files there (after
// shards ran). Exit 0 if every trial completed, 1 if some failed or are
// missing (listed).
int sweep_merge_command(const std::filesystem::path& dir, std::ostream& out);

}  // namespace cnclab
