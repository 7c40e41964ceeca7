#pragma once
// What `cnclab sweep --slurm` submitted, recorded in the sweep folder so that
// a resubmission and `cnclab status` know which trial went to which array
// task:
//
//   slurm/submit-NNN/            one folder per submission (001, 002, ...)
//     sweep.sbatch, merge.sbatch the scripts (slurm_script.hpp)
//     tasks.txt                  line k+1: the trial ids of array task k, comma-separated
//     job.yaml                   array_job, merge_job (written last, atomically, once
//                                sbatch accepted the array: a folder without it was never
//                                submitted and is ignored)
//     logs/task-<k>.out, logs/merge.out
//
// A trial is in flight while an array task it belongs to is queued or
// running (squeue, slurm_queue.hpp); a resubmission leaves those out.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cnclab {

struct SlurmSubmission {
  std::filesystem::path folder;                 // <sweep dir>/slurm/submit-NNN
  std::size_t number = 0;                       // NNN
  std::string array_job;                        // the array's job id
  std::string merge_job;                        // "" when the merge job was not submitted
  std::vector<std::vector<std::string>> tasks;  // trial ids per array task
};

// Trial ids split into `tasks` lists round-robin (trial i to list i mod
// tasks, as shards split a plan); tasks 0 = one list per trial.
std::vector<std::vector<std::string>> split_into_tasks(const std::vector<std::string>& ids,
                                                       std::size_t tasks);

// Creates the next free <root>/submit-NNN (and its logs/), NNN one above the
// highest there; two submitters never share one. Returns it and NNN.
// IoError naming the folder.
std::pair<std::filesystem::path, std::size_t> create_submission_folder(
    const std::filesystem::path& root);

// Creates the next free <dir>/slurm/submit-NNN (and its logs/) and writes
// tasks.txt. IoError naming the folder.
SlurmSubmission create_submission(const std::filesystem::path& dir,
                                  std::vector<std::vector<std::string>> tasks);

// Writes job.yaml: from then on the submission counts.
void record_jobs(SlurmSubmission& submission, const std::string& array_job,
                 const std::string& merge_job);

// The recorded submissions of a sweep folder, oldest first (folders without
// job.yaml skipped). IoError naming a malformed file.
std::vector<SlurmSubmission> read_submissions(const std::filesystem::path& dir);

// Where a trial went: each submission that holds it (oldest first) and its
// array task there.
struct TrialPlacement {
  const SlurmSubmission* submission = nullptr;
  std::size_t task = 0;
};
std::map<std::string, std::vector<TrialPlacement>> trial_placements(
    const std::vector<SlurmSubmission>& submissions);

}  // namespace cnclab
