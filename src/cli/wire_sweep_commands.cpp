// CLI11 wiring of sweep and sweep merge (cli_wiring.hpp).
#include <iostream>
#include <memory>
#include <vector>

#include "cli/cli_wiring.hpp"
#include "cli/slurm_command.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/pipeline/slurm_commands.hpp"
#include "cnclab/pipeline/sweep_command.hpp"

namespace cnclab {
namespace {

struct SweepArgs {
  SweepCommandOptions options;
  std::string experiment;
  std::vector<std::string> words;
  std::optional<std::string> seed_text, sweep_seed_text;
  SlurmSweepOptions slurm;
};

void add_sweep_options(CLI::App& sweep, SweepArgs& a) {
  sweep
      .add_option("experiment", a.experiment,
                  "Experiment YAML file, or a kind: sweep file (its experiment, overrides and "
                  "sweep block; trials go to <out>/<its name>/sweep-<plan hash>)")
      ->check(CLI::ExistingFile);
  sweep.add_option("parameters", a.words,
                   "key=value overrides and swept keys: key=v1,v2,...  key=choice(a,b)  "
                   "key=int_range(lo,hi[,step])  key=uniform(lo,hi)  key=log_uniform(lo,hi); "
                   "k1+k2=v1,v2 sets both keys to each value");
  SweepCommandOptions& o = a.options;
  sweep
      .add_option("--jobs,-j", o.jobs,
                  "Trials at once (default: the number of cores this process may use)")
      ->check(count_validator());
  sweep
      .add_option("--trial-timeout", o.trial_timeout,
                  "Kill a trial running longer than SECONDS; it is recorded as failed "
                  "(timeout) and a resume runs it again only with --retry-failed")
      ->type_name("SECONDS")
      ->check(CLI::PositiveNumber);
  sweep.add_flag("--retry-failed", o.retry_failed,
                 "Run the failed trials (failed results, timeouts) again");
  sweep.add_flag("--rerun", o.rerun,
                 "Train every trial again, also those with a result in the sweep folder or the "
                 "result store, whose file stays (a trial another process trains meanwhile is "
                 "left to it)");
  sweep.add_option("--shard", o.shard,
                   "K/N: run only shard K of N (trials K, K+N, ...), e.g. one per Slurm task");
  sweep.add_option("--dir", o.dir, "Sweep folder (default: <out>/<name>/sweep-<plan hash>)");
  sweep.add_option("--repeats", o.repeats, "Runs per point with derived seeds")
      ->check(count_validator());
  sweep.add_option("--trials", o.trials, "Random search: number of points")
      ->check(count_validator());
  sweep.add_option("--method", o.method,
                   "grid, random, or an Optuna sampler: tpe, cmaes, nsga2, qmc (a study in the "
                   "sweep folder; needs python3-optuna)");
  sweep.add_option("--objective", o.objective,
                   "METRIC[:min|max] to rank trials by, e.g. validation.rmse (a name without "
                   "split: its validation value; default: the validation value of the first "
                   "metric; test.* warns: it selects on test data)");
  sweep
      .add_option("--sweep-seed", a.sweep_seed_text,
                  "Seed of the random search (default: the experiment seed)")
      ->type_name("UINT");
  add_seed_option(sweep, a.seed_text);
  add_store_options(sweep, o.common.results_dir, o.common.datasets_dir);
  sweep.add_flag("--regenerate", o.common.regenerate, "Regenerate the datasets even when cached");
  add_quiet_flag(sweep, o.common.quiet);
  add_profile_option(sweep, o.common.profile);
  add_slurm_sweep_options(sweep, a.slurm, o);
  sweep.footer(
      "Examples:\n"
      "  cnclab sweep experiments/friedman/friedman1_mlp.yaml "
      "model.dropout.keep_probability=0.8,0.9,1.0 trainer.epochs=50 --repeats 3\n"
      "  cnclab sweep experiments/friedman/friedman1_mlp.yaml "
      "'trainer.learning_rate=log_uniform(1e-4,1e-1)' --trials 20 --objective "
      "validation.rmse:min\n"
      "  cnclab sweep experiments/contour_error/architecture.yaml --shard 1/2   # a kind: sweep "
      "file\n"
      "Re-running the same command resumes: trials with a result are skipped.\n"
      "Exit codes: 0 all trials complete, 1 some failed, 2 bad sweep, 128+N interrupted by "
      "signal N.");
}

}  // namespace

void add_sweep_commands(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<SweepArgs>();
  auto* sweep = app.add_subcommand(
      "sweep", "Run many trials of an experiment (grid or random search, repeats), in parallel");
  add_sweep_options(*sweep, *a);

  auto merge_dir = std::make_shared<std::filesystem::path>();
  auto* merge =
      sweep->add_subcommand("merge", "Build summary.h5 of a sweep folder from its trials");
  merge->add_option("dir", *merge_dir, "Sweep folder")->required()->check(CLI::ExistingDirectory);
  merge->footer("Example:\n  cnclab sweep merge results/friedman1_mlp/sweep-1a2b3c4d");
  merge->callback([merge_dir, &action] {
    action = [merge_dir] { return sweep_merge_command(*merge_dir, std::cout); };
  });

  // CLI11 runs the parent's callback after merge's: merge's action stands.
  sweep->callback([sweep, merge, a, &action] {
    if (merge->parsed()) return;
    apply_profile_dir(*sweep, "--out", a->options.common.profile, a->options.common.results_dir);
    action = [a] {
      if (a->experiment.empty()) throw ConfigError("sweep: an experiment file is required");
      a->options.sweep_seed = seed_option(a->sweep_seed_text, "--sweep-seed");
      if (a->slurm.enabled) {
        return slurm_sweep_command(a->experiment, a->words, seed_option(a->seed_text, "--seed"),
                                   a->options, a->slurm.options(), std::cout, std::cerr);
      }
      return sweep_command(a->experiment, a->words, seed_option(a->seed_text, "--seed"), a->options,
                           std::cout, std::cerr);
    };
  });
  add_status_command(app, action);
}

}  // namespace cnclab
