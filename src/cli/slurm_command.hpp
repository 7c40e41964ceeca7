#pragma once
// The --slurm options of `cnclab sweep` and `cnclab reproduce`, and `cnclab
// status` (wire_slurm_commands.cpp); the bodies: pipeline/slurm_commands.hpp,
// pipeline/status_command.hpp.
#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli/cli_wiring.hpp"
#include "cnclab/pipeline/sweep_prepare.hpp"
#include "cnclab/sweep/slurm_script.hpp"

namespace cnclab {

struct SlurmSweepOptions {
  bool enabled = false;  // --slurm
  SlurmOptions slurm;
  // The flags that may override a `slurm:` block, by block key.
  std::vector<std::pair<std::string, const CLI::Option*>> block_flags;
  // `slurm` with `given` set: the block keys whose flags were given.
  SlurmOptions options() const;
};

// --slurm, --dry-run, --partition, ... and --trial-ids on `cnclab sweep`
// (wire_sweep_commands.cpp).
void add_slurm_sweep_options(CLI::App& sweep, SlurmSweepOptions& slurm,
                             SweepCommandOptions& options);
// The same --slurm options on `cnclab reproduce`.
void add_slurm_reproduce_options(CLI::App& reproduce, SlurmSweepOptions& slurm);
// `cnclab status`.
void add_status_command(CLI::App& app, CommandAction& action);

}  // namespace cnclab
