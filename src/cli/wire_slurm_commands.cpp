// CLI11 wiring of `cnclab sweep --slurm ...` and `cnclab status`
// (slurm_command.hpp).
#include <iostream>
#include <memory>

#include "cli/slurm_command.hpp"

namespace cnclab {

void add_slurm_sweep_options(CLI::App& sweep, SlurmSweepOptions& s, SweepCommandOptions& o) {
  SlurmOptions& so = s.slurm;
  auto* slurm = sweep.add_flag(
      "--slurm", s.enabled,
      "Submit the trials still to run as a Slurm job array (sbatch) plus a merge job "
      "after it, and return; run again to resubmit what is missing or failed");
  sweep.add_flag("--dry-run", so.dry_run, "With --slurm: print the scripts, submit nothing");
  sweep.add_option("--partition", so.partition, "With --slurm: #SBATCH --partition");
  sweep.add_option("--time", so.time, "With --slurm: #SBATCH --time (per array task)");
  sweep
      .add_option("--cpus-per-task", so.cpus_per_task,
                  "With --slurm: cores per array task, also its trials at once")
      ->capture_default_str()
      ->check(count_validator());
  sweep.add_option("--mem", so.mem, "With --slurm: #SBATCH --mem per task, e.g. 4G");
  sweep
      .add_option("--max-concurrent", so.max_concurrent,
                  "With --slurm: array tasks running at once (the %K throttle; 0: no limit)")
      ->check(count_validator());
  sweep
      .add_option("--tasks", so.tasks,
                  "With --slurm: array tasks, trials dealt round-robin (default: one per trial)")
      ->check(count_validator());
  sweep
      .add_option("--signal", so.signal,
                  "With --slurm: warning SIG@SECONDS before a kill; the task then starts no "
                  "trial, lets the running ones finish and requeues itself")
      ->capture_default_str();
  for (const char* name : {"--dry-run", "--partition", "--time", "--cpus-per-task", "--mem",
                           "--max-concurrent", "--tasks", "--signal"}) {
    sweep.get_option(name)->needs(slurm);
  }
  sweep.add_option("--trial-ids", o.trial_ids, "Run only these trials (ids from sweep.yaml)")
      ->delimiter(',')
      ->type_name("ID,...");
}

void add_status_command(CLI::App& app, CommandAction& action) {
  auto dir = std::make_shared<std::filesystem::path>();
  auto* status = app.add_subcommand(
      "status",
      "Trials of a sweep folder: complete, failed, running, pending (Slurm), best so far");
  status->add_option("dir", *dir, "Sweep folder")->required()->check(CLI::ExistingDirectory);
  status->footer("Example:\n  cnclab status results/friedman1_mlp/sweep-1a2b3c4d");
  status->callback([dir, &action] { action = [dir] { return status_command(*dir, std::cout); }; });
}

}  // namespace cnclab
