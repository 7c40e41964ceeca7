#pragma once
// `cnclab reproduce --slurm` (its rules: pipeline/reproduce_slurm.hpp) and
// `cnclab status RESULTS` for its record.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/sweep/slurm_script.hpp"

namespace cnclab {

// Exit 0 when everything needed is submitted (or nothing is needed), 1 when
// a node could not be (its upstream failed to load), 2 for a configuration
// error. Error when sbatch is missing or rejects a script: what was
// submitted before is recorded, nothing after it is submitted.
int reproduce_slurm_command(const std::vector<std::string>& paths, const CommandOptions& options,
                            const SlurmOptions& slurm, std::ostream& out, std::ostream& log);

// `cnclab status RESULTS` for a results folder with a reproduce --slurm
// record: each recorded job, its state (squeue) and whether its output exists.
int reproduce_status_command(const std::filesystem::path& results_dir, std::ostream& out);

}  // namespace cnclab
