#pragma once
// `cnclab sweep ... --slurm` (a sweep as a Slurm job array plus a merge job;
// the submission and its resubmission rule: slurm_sweep_submit.hpp) and
// `cnclab reproduce --slurm` (its rules: reproduce_slurm.hpp).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/pipeline/sweep_prepare.hpp"
#include "cnclab/sweep/slurm_script.hpp"

namespace cnclab {

// Submits the sweep's trials still to run as one job array (returns once
// sbatch accepted it; nothing of ours keeps running). Exit 0 when submitted
// or nothing is left to submit. Error (exit 1) when sbatch is missing or
// rejects the submission: the sweep folder then holds no record of it.
int slurm_sweep_command(const std::filesystem::path& experiment,
                        const std::vector<std::string>& words, std::optional<std::uint64_t> seed,
                        const SweepCommandOptions& options, const SlurmOptions& slurm,
                        std::ostream& out, std::ostream& log);

// Exit 0 when everything needed is submitted (or nothing is needed), 1 when
// a node could not be (its upstream failed to load), 2 for a configuration
// error. Error when sbatch is missing or rejects a script: what was
// submitted before is recorded, nothing after it is submitted.
int reproduce_slurm_command(const std::vector<std::string>& paths, const CommandOptions& options,
                            const SlurmOptions& slurm, std::ostream& out, std::ostream& log);

}  // namespace cnclab
