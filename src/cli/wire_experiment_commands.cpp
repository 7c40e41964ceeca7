// CLI11 wiring of run, validate, show, reproduce and compare (cli_wiring.hpp).
#include <iostream>
#include <memory>
#include <vector>

#include "cli/cli_wiring.hpp"
#include "cli/commands.hpp"
#include "cli/slurm_command.hpp"
#include "cnclab/core/config_abbreviate.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/pipeline/reproduce_command.hpp"
#include "cnclab/pipeline/slurm_commands.hpp"
#include "cnclab/report/compare.hpp"
#include "cnclab/report/compare_groups.hpp"

namespace cnclab {
namespace {

const std::string kFullHelp =
    "Print every array of the config in full; without it, an array of more than " +
    std::to_string(kAbbreviateScalars) +
    " numbers in total (nested lists counted through, e.g. a NURBS surface's control points) "
    "prints as its shape and a hash: control_points: 16 × 16 × 3, hash 1a2b3c4d";

// What `run` and `validate` read.
struct ExperimentArgs {
  CommandOptions common;
  std::string experiment;
  std::vector<std::string> overrides;
  std::optional<std::string> seed_text;
};

void add_run(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<ExperimentArgs>();
  auto* run = app.add_subcommand("run", "Run one experiment and write its HDF5 result");
  run->add_option("experiment", a->experiment, "Experiment YAML file")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("overrides", a->overrides,
                  "Config overrides key=value, values typed as YAML (1e-4, true, [28, 20])");
  add_seed_option(*run, a->seed_text);
  add_store_options(*run, a->common.results_dir, a->common.datasets_dir);
  add_quiet_flag(*run, a->common.quiet);
  run->add_flag("--regenerate", a->common.regenerate, "Regenerate the dataset even when cached");
  add_profile_option(*run, a->common.profile);
  run->footer(
      "Example:\n  cnclab run experiments/friedman/friedman1_mlp.yaml trainer.learning_rate=1e-3 "
      "model.hidden=[32,16] --seed 7\nWrites results/<name>/<name>-seed<N>-<hash>.h5 atomically.");
  run->callback([run, a, &action] {
    apply_profile_dir(*run, "--out", a->common.profile, a->common.results_dir);
    action = [a] {
      return run_command(a->experiment, a->overrides, seed_option(a->seed_text, "--seed"),
                         a->common, std::cout, std::cerr);
    };
  });
}

void add_validate(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<ExperimentArgs>();
  auto* validate = app.add_subcommand(
      "validate", "Check an experiment config and print it resolved; writes nothing");
  validate->add_option("experiment", a->experiment, "Experiment YAML file")
      ->required()
      ->check(CLI::ExistingFile);
  validate->add_option("overrides", a->overrides, "Config overrides key=value");
  add_seed_option(*validate, a->seed_text);
  add_profile_option(*validate, a->common.profile);
  validate->add_flag("--full", a->common.full, kFullHelp);
  validate->footer(
      "Example:\n  cnclab validate experiments/friedman/friedman1_mlp.yaml trainer.momentum=0.9");
  validate->callback([a, &action] {
    action = [a] {
      return validate_command(a->experiment, a->overrides, seed_option(a->seed_text, "--seed"),
                              a->common, std::cout);
    };
  });
}

void add_show(CLI::App& app, CommandAction& action) {
  auto paths = std::make_shared<std::vector<std::string>>();
  auto options = std::make_shared<CommandOptions>();
  auto* show = app.add_subcommand(
      "show",
      "Print a result file (config, provenance, metrics, training) or a sweep's summary.h5");
  show->add_option("result", *paths, "Result HDF5 file(s) or a sweep's summary.h5")
      ->required()
      ->check(CLI::ExistingFile);
  show->add_flag("--full", options->full, kFullHelp);
  show->footer(
      "Examples:\n  cnclab show results/friedman1_mlp/friedman1_mlp-seed42-*.h5\n"
      "  cnclab show results/friedman1_mlp/sweep-1a2b3c4d/summary.h5   # the ranking, as "
      "`cnclab sweep merge` prints it; nothing rewritten");
  show->callback([paths, options, &action] {
    action = [paths, options] { return show_command(*paths, *options, std::cout); };
  });
}

struct ReproduceArgs {
  CommandOptions common;
  std::vector<std::string> paths;
  bool quick = false;
  SlurmSweepOptions slurm;  // --slurm and its options
};

void add_reproduce(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<ReproduceArgs>();
  auto* reproduce = app.add_subcommand(
      "reproduce", "Run experiments (default: all under experiments/) and print their metrics");
  reproduce->add_option("paths", a->paths, "Experiment files or folders (default: experiments)");
  add_store_options(*reproduce, a->common.results_dir, a->common.datasets_dir);
  add_quiet_flag(*reproduce, a->common.quiet);
  reproduce->add_flag("--force", a->common.force,
                      "Run every experiment even if its result is current");
  reproduce->add_flag("--regenerate", a->common.regenerate, "Regenerate datasets even when cached");
  add_profile_option(*reproduce, a->common.profile);
  reproduce
      ->add_option("--jobs,-j", a->common.jobs,
                   "Experiments trained at once, each in its own process, once their "
                   "upstream results are ready (default: the number of cores this process "
                   "may use; 1 shows each run's progress)")
      ->check(count_validator());
  reproduce->add_flag("--check", a->common.check,
                      "Check each printed table's declared targets (configs/studies/*.yaml "
                      "targets:); PASS/FAIL per target, exit 1 on any FAIL");
  reproduce->add_flag("--quick", a->quick,
                      "Same as --profile quick: fewer epochs and samples, same code paths "
                      "(about a minute per study; ROOT/quick)");
  add_slurm_reproduce_options(*reproduce, a->slurm);
  reproduce->footer(
      "Example:\n  cnclab reproduce                  # everything\n  cnclab reproduce "
      "experiments/friedman\n"
      "Experiments run upstream first (needs:, init_from:, a job's predictor:); a result whose "
      "resolved config and upstream results are unchanged is reused. Each line says ran/reused "
      "and why.\n"
      "  cnclab reproduce --quick experiments/step_error   # the quick profile\n"
      "  cnclab reproduce --check   # and check the studies' targets (exit 1 on a FAIL)\n"
      "  cnclab reproduce experiments/ik experiments/ik_search --slurm --partition short "
      "--time 01:00:00   # as Slurm jobs");
  reproduce->callback([reproduce, a, &action] {
    if (a->quick) {
      if (!a->common.profile.empty() && a->common.profile != "quick") {
        throw CLI::ValidationError("--quick and --profile " + a->common.profile + " contradict");
      }
      a->common.profile = "quick";
    }
    apply_profile_dir(*reproduce, "--out", a->common.profile, a->common.results_dir);
    action = [a] {
      if (a->slurm.enabled) {
        return reproduce_slurm_command(a->paths, a->common, a->slurm.options(), std::cout,
                                       std::cerr);
      }
      return reproduce_command(a->paths, a->common, std::cout, std::cerr);
    };
  });
}

struct CompareArgs {
  std::vector<std::string> runs;
  std::string format = "table";
  GroupCompareOptions groups;  // --group-by, --alpha, --pool, --full
};

void add_compare(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<CompareArgs>();
  auto* compare = app.add_subcommand(
      "compare", "Runs side by side: the config keys that differ and the metrics with deltas");
  compare->add_option("runs", a->runs, "Result files, run folders or sweep folders")
      ->required()
      ->check(CLI::ExistingPath);
  compare->add_option("--format", a->format, "table, md, csv or json")->capture_default_str();
  compare->add_flag("--full", a->groups.full, kFullHelp);
  auto* group_by = compare->add_option(
      "--group-by", a->groups.group_by,
      "Group the runs by this config key (trainer.type), or 'repeats' (configs equal apart from "
      "seed); each metric as mean with its confidence interval (clipped to the metric's range), "
      "each group against the first by Welch's t-test, a bootstrap interval and, for runs "
      "paired by seed, the paired t-test and Wilcoxon signed-rank test; within each combination "
      "of the other keys that vary inside the groups");
  compare
      ->add_option("--alpha", a->groups.alpha,
                   "With --group-by: significance level; intervals at 1 - alpha")
      ->capture_default_str()
      ->needs(group_by);
  compare
      ->add_flag("--pool", a->groups.pool,
                 "With --group-by: compare across the other keys that vary inside the groups "
                 "(named in the output) instead of within each combination of them")
      ->needs(group_by);
  compare->footer(
      "Examples:\n  cnclab compare results/friedman1_mlp/a.h5 results/friedman1_mlp/b.h5\n"
      "  cnclab compare results/friedman1_mlp/sweep-1a2b3c4d --format md\n"
      "  cnclab compare results/narx/sweep-1a2b3c4d --group-by trainer.type --alpha 0.01");
  compare->callback([a, &action] {
    action = [a] {
      if (!a->groups.group_by.empty()) {
        return compare_groups_command(a->runs, a->format, a->groups, std::cout);
      }
      return compare_command(a->runs, a->format, a->groups.full, std::cout);
    };
  });
}

}  // namespace

void add_experiment_commands(CLI::App& app, CommandAction& action) {
  add_run(app, action);
  add_validate(app, action);
  add_show(app, action);
  add_reproduce(app, action);
  add_compare(app, action);
}

}  // namespace cnclab
