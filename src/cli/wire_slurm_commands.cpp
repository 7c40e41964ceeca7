// CLI11 wiring of `cnclab sweep --slurm ...` and `cnclab status`
// (slurm_command.hpp).
#include <algorithm>
#include <iostream>
#include <memory>

#include "cli/slurm_command.hpp"
#include "cnclab/pipeline/status_command.hpp"
#include "cnclab/sweep/slurm_fields.hpp"

namespace cnclab {

namespace {

// The options both `sweep --slurm` and `reproduce --slurm` take, each
// needing --slurm.
void add_slurm_options(CLI::App& app, SlurmSweepOptions& s, const std::string& slurm_help) {
  SlurmOptions& so = s.slurm;
  auto* slurm = app.add_flag("--slurm", s.enabled, slurm_help);
  app.add_flag("--dry-run", so.dry_run, "With --slurm: print the scripts, submit nothing");
  app.add_option("--partition", so.partition, "With --slurm: #SBATCH --partition");
  app.add_option("--time", so.time, "With --slurm: #SBATCH --time (per job or array task)");
  app.add_option("--cpus-per-task", so.cpus_per_task,
                 "With --slurm: cores per job or array task, also a task's trials at once")
      ->capture_default_str()
      ->check(count_validator());
  app.add_option("--mem", so.mem, "With --slurm: #SBATCH --mem per job or task, e.g. 4G");
  app.add_option("--max-concurrent", so.max_concurrent,
                 "With --slurm: array tasks running at once (the %K throttle; 0: no limit)")
      ->check(count_validator());
  app.add_option("--tasks", so.tasks,
                 "With --slurm: array tasks, trials dealt round-robin (default: one per trial); "
                 "a model-based study: at most this many worker tasks (default: one per trial "
                 "it lacks)")
      ->check(count_validator());
  app.add_option("--signal", so.signal,
                 "With --slurm: warning SIG@SECONDS before a kill; an array task then starts no "
                 "trial, lets the running ones finish and requeues itself")
      ->capture_default_str();
  for (const char* name : {"--dry-run", "--partition", "--time", "--cpus-per-task", "--mem",
                           "--max-concurrent", "--tasks", "--signal"}) {
    app.get_option(name)->needs(slurm);
  }
  // Each slurm: block key is the flag's name with '_' for '-'.
  for (const auto& key : slurm_fields().keys()) {
    std::string flag = "--" + key;
    std::replace(flag.begin(), flag.end(), '_', '-');
    s.block_flags.emplace_back(key, app.get_option(flag));
  }
}

}  // namespace

SlurmOptions SlurmSweepOptions::options() const {
  SlurmOptions o = slurm;
  o.given.clear();
  for (const auto& [key, flag] : block_flags) {
    if (flag->count() > 0) o.given.push_back(key);
  }
  return o;
}

void add_slurm_sweep_options(CLI::App& sweep, SlurmSweepOptions& s, SweepCommandOptions& o) {
  add_slurm_options(sweep, s,
                    "Submit the trials still to run as a Slurm job array (sbatch) plus a merge "
                    "job after it, and return; run again to resubmit what is missing or failed");
  sweep.add_option("--trial-ids", o.trial_ids, "Run only these trials (ids from sweep.yaml)")
      ->delimiter(',')
      ->type_name("ID,...");
}

void add_slurm_reproduce_options(CLI::App& reproduce, SlurmSweepOptions& s) {
  add_slurm_options(reproduce, s,
                    "Submit the experiments to run as Slurm jobs with afterok dependencies "
                    "along needs:/init_from: (sweeps as job arrays), reusing current results, "
                    "and return; run again to submit what is missing or failed");
}

void add_status_command(CLI::App& app, CommandAction& action) {
  auto dir = std::make_shared<std::filesystem::path>();
  auto* status = app.add_subcommand(
      "status",
      "A sweep folder's trials (complete, failed, running, pending, best so far), or a results "
      "folder's sweeps and `reproduce --slurm` jobs");
  status->add_option("dir", *dir, "Sweep folder, or a results folder")
      ->required()
      ->check(CLI::ExistingDirectory);
  status->footer(
      "Examples:\n  cnclab status results/friedman1_mlp/sweep-1a2b3c4d\n  cnclab status results");
  status->callback([dir, &action] { action = [dir] { return status_command(*dir, std::cout); }; });
}

}  // namespace cnclab
