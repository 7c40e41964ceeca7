#pragma once
// `cnclab sweep ... --slurm`'s submission: the trials still to run (neither
// done nor queued or running, slurm_queue_view.hpp) as one job array plus a
// merge (or final) job, through Slurm's client tools (sweep/slurm_tools.hpp).
//
// Resubmission rule: a trial is submitted when the sweep folder has no result
// for it (failed ones too with --retry-failed, as a local resume) and no
// array task holding it is queued or running (squeue). A done trial or one in
// flight is never submitted again.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/pipeline/sweep_prepare.hpp"
#include "cnclab/sweep/slurm_script.hpp"

namespace cnclab {

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

}  // namespace cnclab
