#pragma once
// `cnclab sweep ... --slurm` (submit a sweep as a Slurm job array plus a
// merge job, and resubmit what is missing) and `cnclab status SWEEP_DIR`.
// The submission itself and its resubmission rule: pipeline/slurm_sweep_submit.hpp.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cli/cli_wiring.hpp"
#include "cli/sweep_command.hpp"
#include "cnclab/pipeline/slurm_sweep_submit.hpp"

namespace cnclab {

struct SlurmSweepOptions {
  bool enabled = false;  // --slurm
  SlurmOptions slurm;
  // The flags that may override a `slurm:` block, by block key.
  std::vector<std::pair<std::string, const CLI::Option*>> block_flags;
  // `slurm` with `given` set: the block keys whose flags were given.
  SlurmOptions options() const;
};

// Submits the sweep's trials still to run as one job array (returns once
// sbatch accepted it; nothing of ours keeps running). Exit 0 when submitted
// or nothing is left to submit. Error (exit 1) when sbatch is missing or
// rejects the submission: the sweep folder then holds no record of it.
int slurm_sweep_command(const std::filesystem::path& experiment,
                        const std::vector<std::string>& words, std::optional<std::uint64_t> seed,
                        const SweepCommandOptions& options, const SlurmOptions& slurm,
                        std::ostream& out, std::ostream& log);

// A sweep folder: trials complete / failed / running (a Slurm task, or a
// process holding the trial's lock) / pending / not queued, the array tasks'
// states (squeue; sacct when accounting is on), the best trial so far.
// Another folder: results_status_command.
int status_command(const std::filesystem::path& dir, std::ostream& out);
// A results folder (status_command.cpp): the jobs `reproduce --slurm`
// submitted into it, and every sweep folder below it, one line each.
// ConfigError when it has neither.
int results_status_command(const std::filesystem::path& dir, std::ostream& out);

// --slurm, --dry-run, --partition, ... and --trial-ids on `cnclab sweep`
// (wire_sweep_commands.cpp).
void add_slurm_sweep_options(CLI::App& sweep, SlurmSweepOptions& slurm,
                             SweepCommandOptions& options);
// The same --slurm options on `cnclab reproduce` (reproduce_slurm.hpp).
void add_slurm_reproduce_options(CLI::App& reproduce, SlurmSweepOptions& slurm);
// `cnclab status`.
void add_status_command(CLI::App& app, CommandAction& action);

}  // namespace cnclab
