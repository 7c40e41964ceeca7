#pragma once
// `cnclab sweep ... --slurm` (submit a sweep as a Slurm job array plus a
// merge job, and resubmit what is missing) and `cnclab status SWEEP_DIR`.
// Slurm is reached only through its client tools (sweep/slurm_tools.hpp).
//
// Resubmission rule: a trial is submitted when the sweep folder has no result
// for it (failed ones too with --retry-failed, as a local resume) and no
// array task holding it is queued or running (squeue). A done trial or one in
// flight is never submitted again.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cli/cli_wiring.hpp"
#include "cli/sweep_command.hpp"
#include "cnclab/sweep/slurm_script.hpp"

namespace cnclab {

struct SlurmSweepOptions {
  bool enabled = false;  // --slurm
  SlurmOptions slurm;
};

// Submits the sweep's trials still to run as one job array (returns once
// sbatch accepted it; nothing of ours keeps running). Exit 0 when submitted
// or nothing is left to submit. Error (exit 1) when sbatch is missing or
// rejects the submission: the sweep folder then holds no record of it.
int slurm_sweep_command(const std::filesystem::path& experiment,
                        const std::vector<std::string>& words, std::optional<std::uint64_t> seed,
                        const SweepCommandOptions& options, const SlurmOptions& slurm,
                        std::ostream& out, std::ostream& log);

// Trials complete / failed / running / pending / not queued, the array
// tasks' states (squeue; sacct when accounting is on), the best trial so far.
int status_command(const std::filesystem::path& dir, std::ostream& out);

// --slurm, --dry-run, --partition, ... and --trial-ids on `cnclab sweep`
// (wire_sweep_commands.cpp).
void add_slurm_sweep_options(CLI::App& sweep, SlurmSweepOptions& slurm,
                             SweepCommandOptions& options);
// `cnclab status`.
void add_status_command(CLI::App& app, CommandAction& action);

}  // namespace cnclab
