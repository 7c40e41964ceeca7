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

// Job names: "cnclab-<name><suffix>", characters other than letters,
// digits, '-', '_' as '_' (sbatch's #SBATCH lines split at spaces).
std::string slurm_job_name(const std::string& name, const char* suffix);

// Runs `sbatch --parsable ARGS...` and returns the job id. Error "sbatch
// rejected WHAT (exit N): its message".
std::string submit_batch(const std::vector<std::string>& args, const std::string& what);

// sbatch, squeue and scontrol on PATH, or an Error saying --slurm needs them.
void check_slurm_clients();

// A sweep's submission within `reproduce --slurm`: the array waits for the
// upstream jobs, and its final job makes the sweep job's result.
struct SweepSlurmRequest {
  std::string after;  // the array's dependency ("afterany:12:13"); "" none
  // The job after the array (and after earlier arrays still in flight),
  // submitted even when no trial is left to submit; empty: `cnclab sweep
  // merge DIR`, and nothing when no trial is left (plain `sweep --slurm`).
  std::vector<std::string> final_command;
};
struct SweepSlurmResult {
  std::filesystem::path dir;
  std::size_t total = 0, to_submit = 0, done = 0, in_flight = 0;  // trials
  std::string array_job, final_job;  // "" when not submitted (or a dry run)
  bool final_rejected = false;       // plain sweep --slurm: merge by hand
};
// The body of `sweep --slurm` (options checked by the caller): submits the
// trials neither done nor in flight as an array plus its final job, or
// prints them (dry run). Error when sbatch rejects a script.
SweepSlurmResult submit_sweep_slurm(const std::filesystem::path& experiment,
                                    const std::vector<std::string>& words,
                                    std::optional<std::uint64_t> seed,
                                    const SweepCommandOptions& options, const SlurmOptions& slurm,
                                    const SweepSlurmRequest& request, std::ostream& out,
                                    std::ostream& log);

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
