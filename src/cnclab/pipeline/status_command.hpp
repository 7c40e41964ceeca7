#pragma once
// `cnclab status DIR`: a sweep folder's trials, or a results folder's sweeps
// and `reproduce --slurm` jobs.
#include <filesystem>
#include <ostream>

namespace cnclab {

// A sweep folder: trials complete / failed / running (a Slurm task, or a
// process holding the trial's lock) / pending / not queued, the array tasks'
// states (squeue; sacct when accounting is on), the best trial so far.
// Another folder: results_status_command.
int status_command(const std::filesystem::path& dir, std::ostream& out);
// A results folder: the jobs `reproduce --slurm` submitted into it
// (reproduce_status_command), and every sweep folder below it, one line each.
// ConfigError when it has neither.
int results_status_command(const std::filesystem::path& dir, std::ostream& out);
// A results folder's reproduce --slurm record: each recorded job, its state
// (squeue) and whether its output exists.
int reproduce_status_command(const std::filesystem::path& results_dir, std::ostream& out);

}  // namespace cnclab
