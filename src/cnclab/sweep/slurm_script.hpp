#pragma once
// The sbatch scripts of `cnclab sweep --slurm`: a job array whose task k runs
// the trials listed on line k + 1 of the submission's tasks.txt (the same
// `cnclab sweep` command with --trial-ids, so a task plans, resumes and
// writes results exactly as a local run does), and a merge job that builds
// summary.h5 once the array has ended.
//
// Pre-emption and time limits: the array asks Slurm for a warning signal
// before the kill (`#SBATCH --signal=B:USR1@120`, SlurmOptions::signal) and
// may be requeued (`--requeue`). On the signal the batch shell passes USR1 to
// cnclab, which starts no new trial and lets the running ones finish
// (trial_pool.hpp); a running trial still busy half the warning time later is
// abandoned (SIGTERM: its partial file is never read as a result). If trials
// of the task were left, the task requeues itself (`scontrol requeue`), and
// when it runs again it skips the trials that have a result.
#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace cnclab {

// What a submission asks of Slurm. An empty string leaves the setting to the
// cluster: its defaults and sbatch's input environment (SBATCH_PARTITION,
// SBATCH_TIMELIMIT, ... as set by the site or the user).
struct SlurmOptions {
  std::string partition;            // #SBATCH --partition
  std::string time;                 // #SBATCH --time, e.g. 02:00:00 or 1-00:00:00
  std::size_t cpus_per_task = 1;    // #SBATCH --cpus-per-task; also trials at once in a task
  std::string mem;                  // #SBATCH --mem, e.g. 4G
  std::size_t max_concurrent = 0;   // array throttle (%K): tasks running at once; 0 = no limit
  std::string signal = "USR1@120";  // warning SIG@SECONDS before a kill (#SBATCH --signal=B:...)
  std::size_t tasks = 0;            // array tasks; 0 = one per trial to run (<= kMaxArrayTasks)
  bool dry_run = false;             // print the scripts, submit and write nothing
  // The keys (slurm_fields.hpp) set on the command line: they win over a
  // file's `slurm:` block (resolve_slurm_options).
  std::vector<std::string> given;
  // ConfigError naming the option: cpus_per_task 0, a signal not NAME@SECONDS
  // (NAME one of USR1, USR2; SECONDS 10..65535), a time or partition with spaces.
  void validate() const;
  std::string signal_name() const;  // "USR1"
  int signal_seconds() const;       // 120
};

// Slurm's default MaxArraySize is 1001 (task ids 0..1000).
inline constexpr std::size_t kMaxArrayTasks = 1000;

struct SlurmArrayScript {
  std::string job_name;                   // #SBATCH --job-name
  std::filesystem::path workdir;          // #SBATCH --chdir: where relative paths resolve
  std::filesystem::path submission;       // <sweep dir>/slurm/submit-NNN (logs, tasks.txt)
  std::size_t tasks = 1;                  // array size
  std::vector<std::string> task_command;  // cnclab sweep ... (without --trial-ids / --jobs)
  // A model-based sweep (model_search.hpp): each task runs a worker of the
  // study (no --trial-ids; tasks.txt holds "study" per task) until the study
  // has its trials; a task killed mid-trial leaves it to a resubmission.
  bool study = false;
};

// The job-array script (bash).
std::string array_script(const SlurmOptions& options, const SlurmArrayScript& array);

// The merge job's script: `cnclab sweep merge <sweep dir>`.
std::string merge_script(const SlurmOptions& options, const std::string& job_name,
                         const std::filesystem::path& workdir,
                         const std::filesystem::path& submission, const std::string& cnclab,
                         const std::filesystem::path& sweep_dir);

// One plain job of `cnclab reproduce --slurm` (an experiment's `cnclab run`,
// a `kind:` job, a sweep job's final `cnclab run` after its array): runs
// `command` once. --requeue: a pre-empted job starts again from the
// beginning (a training run keeps no checkpoint; its partial file is never
// read as a result).
struct SlurmJobScript {
  std::string job_name;              // #SBATCH --job-name
  std::string what;                  // a comment line: what the job makes
  std::filesystem::path workdir;     // #SBATCH --chdir
  std::filesystem::path log;         // #SBATCH --output (%j: the job id)
  std::vector<std::string> command;  // cnclab run FILE --out ... (quoted here)
};
std::string job_script(const SlurmOptions& options, const SlurmJobScript& job);

}  // namespace cnclab
