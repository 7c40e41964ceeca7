#pragma once
// What `cnclab reproduce --slurm` submitted, kept in the results folder so
// that a rerun and `cnclab status` see it:
//
//   <results>/reproduce-slurm/
//     jobs.yaml      per experiment or job file, its newest submission (written
//                    atomically after every accepted sbatch)
//     submit-NNN/    one folder per reproduce --slurm: <name>.sbatch, logs/
//
// A sweep job's array and its trials are recorded in its sweep folder as
// `cnclab sweep --slurm` records them (slurm_submission.hpp); jobs.yaml
// holds the job others wait for (the sweep's final job) and the array's id.
//
// A rerun treats an entry as in flight (not submitted again, its job the one
// dependents wait for) while its job is queued or running and its `output` is
// what the file makes now (a changed config makes another result file).
#include <filesystem>
#include <map>
#include <string>

namespace cnclab {

struct ReproduceJobEntry {
  std::string name;    // the experiment's or job's name
  std::string output;  // what it makes: result file, sweep folder, or "" (a kind: job)
  std::string job;     // the job dependents wait for (a sweep's final job)
  std::string array;   // a sweep's array job ("" when none was needed)
  std::string script;  // the script submitted as `job`
};

// Entries by file (absolute and lexically normal: the key of reproduce_file_key).
using ReproduceRecord = std::map<std::string, ReproduceJobEntry>;

// <results>/reproduce-slurm.
std::filesystem::path reproduce_slurm_dir(const std::filesystem::path& results_dir);

// The record's key of an experiment or job file.
std::string reproduce_file_key(const std::filesystem::path& file);

// The record (empty when there is none). IoError naming a malformed file.
ReproduceRecord read_reproduce_record(const std::filesystem::path& results_dir);

// Writes jobs.yaml atomically.
void write_reproduce_record(const std::filesystem::path& results_dir,
                            const ReproduceRecord& record);

}  // namespace cnclab
