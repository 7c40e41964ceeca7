// cnclab command line: CLI11 wiring only; the work is in the library.
// Exit codes: 0 ok, 1 run failed, 2 bad usage or configuration.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

#include "cli/builtins.hpp"
#include "cli/commands.hpp"
#include "cli/dataset_commands.hpp"
#include "cli/schema_command.hpp"
#include "cli/sweep_command.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/report/compare.hpp"
#include "cnclab/report/tables.hpp"

namespace {

constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;
constexpr int kExitUsage = 2;
constexpr const char* kProfileHelp =
    "Apply the experiment files' `profiles: {NAME: ...}` overrides (e.g. quick); results then "
    "default to <results>/NAME";

}  // namespace

int main(int argc, char** argv) {
  cnclab::register_builtins();
  CLI::App app{
      "cnclab: experiments, datasets and paper tables for neural-network studies of CNC "
      "machining error.\n"
      "Example: cnclab run experiments/friedman/friedman1_mlp.yaml trainer.epochs=50"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every subcommand");
  app.footer("Exit codes: 0 ok, 1 run failed, 2 bad usage or configuration.");

  // Counts (--jobs, --repeats, --trials): digits only. CLI11 alone reads "-1"
  // for an unsigned option as 2^64 - 1 (a sweep then plans forever).
  const CLI::Validator count(
      [](std::string& text) {
        const bool digits = !text.empty() && std::all_of(text.begin(), text.end(), [](char c) {
          return c >= '0' && c <= '9';
        });
        return digits ? std::string() : "expected a non-negative integer, got " + text;
      },
      "");

  cnclab::CommandOptions common;
  std::string experiment;
  std::vector<std::string> overrides;
  // Seeds are read as text and checked in the try block below: CLI11 would
  // turn "-1" into 2^64 - 1, and its own errors do not take our error form.
  std::optional<std::string> seed_text, sweep_seed_text;

  auto* run = app.add_subcommand("run", "Run one experiment and write its HDF5 result");
  run->add_option("experiment", experiment, "Experiment YAML file")
      ->required()
      ->check(CLI::ExistingFile);
  run->add_option("overrides", overrides,
                  "Config overrides key=value, values typed as YAML (1e-4, true, [28, 20])");
  run->add_option("--seed", seed_text, "Master seed (overrides the YAML's seed)")
      ->type_name("UINT");
  run->add_option("--out", common.results_dir, "Results folder")->capture_default_str();
  run->add_option("--data-dir", common.datasets_dir, "Dataset cache folder")->capture_default_str();
  run->add_flag("--quiet,-q", common.quiet, "No progress output");
  run->add_flag("--regenerate", common.regenerate, "Regenerate the dataset even when cached");
  run->add_option("--profile", common.profile, kProfileHelp);
  run->footer(
      "Example:\n  cnclab run experiments/friedman/friedman1_mlp.yaml trainer.learning_rate=1e-3 "
      "model.hidden=[32,16] --seed 7\nWrites results/<name>/<name>-seed<N>-<hash>.h5 atomically.");

  auto* validate = app.add_subcommand(
      "validate", "Check an experiment config and print it resolved; writes nothing");
  validate->add_option("experiment", experiment, "Experiment YAML file")
      ->required()
      ->check(CLI::ExistingFile);
  validate->add_option("overrides", overrides, "Config overrides key=value");
  validate->add_option("--seed", seed_text, "Master seed (overrides the YAML's seed)")
      ->type_name("UINT");
  validate->add_option("--profile", common.profile, kProfileHelp);
  validate->footer(
      "Example:\n  cnclab validate experiments/friedman/friedman1_mlp.yaml trainer.momentum=0.9");

  std::vector<std::string> paths;
  auto* show =
      app.add_subcommand("show", "Print a result file: config, provenance, metrics, training");
  show->add_option("result", paths, "Result HDF5 file(s)")->required();
  show->footer("Example:\n  cnclab show results/friedman1_mlp/friedman1_mlp-seed42-*.h5");

  auto* reproduce = app.add_subcommand(
      "reproduce", "Run experiments (default: all under experiments/) and print their metrics");
  reproduce->add_option("paths", paths, "Experiment files or folders (default: experiments)");
  reproduce->add_option("--out", common.results_dir, "Results folder")->capture_default_str();
  reproduce->add_option("--data-dir", common.datasets_dir, "Dataset cache folder")
      ->capture_default_str();
  reproduce->add_flag("--quiet,-q", common.quiet, "No progress output");
  reproduce->add_flag("--force", common.force,
                      "Run every experiment even if its result is current");
  reproduce->add_flag("--regenerate", common.regenerate, "Regenerate datasets even when cached");
  reproduce->add_option("--profile", common.profile, kProfileHelp);
  reproduce
      ->add_option("--jobs,-j", common.jobs,
                   "Experiments trained at once, each in its own process, once their "
                   "upstream results are ready (default: the number of cores this process "
                   "may use; 1 shows each run's progress)")
      ->check(count);
  bool quick = false;
  reproduce->add_flag("--quick", quick,
                      "Same as --profile quick: fewer epochs and samples, same code paths "
                      "(about a minute per study; results/quick)");
  reproduce->footer(
      "Example:\n  cnclab reproduce                  # everything\n  cnclab reproduce "
      "experiments/friedman\n"
      "Experiments run upstream first (needs:, init_from:); a result whose resolved config and "
      "upstream results are unchanged is reused. Each line says ran/reused and why.\n"
      "  cnclab reproduce --quick experiments/step_error   # the quick profile");

  cnclab::SweepCommandOptions sweep_options;
  std::vector<std::string> sweep_words;
  auto* sweep = app.add_subcommand(
      "sweep", "Run many trials of an experiment (grid or random search, repeats), in parallel");
  sweep->add_option("experiment", experiment, "Experiment YAML file")->check(CLI::ExistingFile);
  sweep->add_option("parameters", sweep_words,
                    "key=value overrides and swept keys: key=v1,v2,...  key=choice(a,b)  "
                    "key=int_range(lo,hi[,step])  key=uniform(lo,hi)  key=log_uniform(lo,hi)");
  sweep
      ->add_option("--jobs,-j", sweep_options.jobs,
                   "Trials at once (default: the number of cores this process may use)")
      ->check(count);
  sweep
      ->add_option("--trial-timeout", sweep_options.trial_timeout,
                   "Kill a trial running longer than SECONDS; it is recorded as failed "
                   "(timeout) and a resume runs it again only with --retry-failed")
      ->type_name("SECONDS")
      ->check(CLI::PositiveNumber);
  sweep->add_flag("--retry-failed", sweep_options.retry_failed,
                  "Run the failed trials (failed results, timeouts) again");
  sweep->add_option("--shard", sweep_options.shard,
                    "K/N: run only shard K of N (trials K, K+N, ...), e.g. one per Slurm task");
  sweep->add_option("--dir", sweep_options.dir,
                    "Sweep folder (default: <out>/<name>/sweep-<plan hash>)");
  sweep->add_option("--repeats", sweep_options.repeats, "Runs per point with derived seeds")
      ->check(count);
  sweep->add_option("--trials", sweep_options.trials, "Random search: number of points")
      ->check(count);
  sweep->add_option("--method", sweep_options.method, "grid or random");
  sweep->add_option("--objective", sweep_options.objective,
                    "METRIC[:min|max] to rank trials by (default: first metric)");
  sweep
      ->add_option("--sweep-seed", sweep_seed_text,
                   "Seed of the random search (default: the experiment seed)")
      ->type_name("UINT");
  sweep->add_option("--seed", seed_text, "Master seed (overrides the YAML's seed)")
      ->type_name("UINT");
  sweep->add_option("--out", sweep_options.common.results_dir, "Results folder")
      ->capture_default_str();
  sweep->add_option("--data-dir", sweep_options.common.datasets_dir, "Dataset cache folder")
      ->capture_default_str();
  sweep->add_flag("--regenerate", sweep_options.common.regenerate,
                  "Regenerate the datasets even when cached");
  sweep->add_flag("--quiet,-q", sweep_options.common.quiet, "No progress output");
  sweep->add_option("--profile", sweep_options.common.profile, kProfileHelp);
  sweep->footer(
      "Examples:\n"
      "  cnclab sweep experiments/friedman/friedman1_mlp.yaml "
      "model.dropout.keep_probability=0.8,0.9,1.0 trainer.epochs=50 --repeats 3\n"
      "  cnclab sweep experiments/friedman/friedman1_mlp.yaml "
      "'trainer.learning_rate=log_uniform(1e-4,1e-1)' --trials 20 --objective rmse:min\n"
      "Re-running the same command resumes: trials with a result are skipped.\n"
      "Exit codes: 0 all trials complete, 1 some failed, 2 bad sweep, 128+N interrupted by "
      "signal N.");
  std::string merge_dir;
  auto* merge =
      sweep->add_subcommand("merge", "Build summary.h5 of a sweep folder from its trials");
  merge->add_option("dir", merge_dir, "Sweep folder")->required()->check(CLI::ExistingDirectory);
  merge->footer("Example:\n  cnclab sweep merge results/friedman1_mlp/sweep-1a2b3c4d");

  std::string compare_format = "table";
  auto* compare = app.add_subcommand(
      "compare", "Runs side by side: the config keys that differ and the metrics with deltas");
  compare->add_option("runs", paths, "Result files, run folders or sweep folders")->required();
  compare->add_option("--format", compare_format, "table, md, csv or json")->capture_default_str();
  compare->footer(
      "Examples:\n  cnclab compare results/friedman1_mlp/a.h5 results/friedman1_mlp/b.h5\n"
      "  cnclab compare results/friedman1_mlp/sweep-1a2b3c4d --format md");

  auto* dataset = app.add_subcommand("dataset", "Generate or inspect a dataset file");
  dataset->require_subcommand(1);
  dataset->footer(
      "Example:\n  cnclab dataset generate configs/datasets/step_error_surface1.yaml\n  cnclab "
      "dataset show datasets/step_error_surface1.h5");
  std::optional<std::string> dataset_out;
  auto* generate = dataset->add_subcommand(
      "generate",
      "Generate the dataset a YAML `dataset:` section describes; writes HDF5 atomically");
  generate->add_option("config", experiment, "YAML file with a dataset section")
      ->required()
      ->check(CLI::ExistingFile);
  generate->add_option("overrides", overrides, "Config overrides key=value");
  generate->add_option("--out", dataset_out, "Output file (default datasets/<config stem>.h5)");
  bool dataset_quiet = false;
  generate->add_flag("--quiet,-q", dataset_quiet, "No progress output");
  generate->footer(
      "Example:\n  cnclab dataset generate configs/datasets/step_error_surface1.yaml\n  cnclab "
      "dataset generate configs/datasets/step_error_surface2.yaml dataset.options.lines=20 "
      "--out s2.h5");
  auto* dataset_show = dataset->add_subcommand(
      "show", "Print a dataset file: counts, ranges with units, histogram, convex/concave split");
  dataset_show->add_option("file", experiment, "Dataset HDF5 file")->required();
  dataset_show->footer("Example:\n  cnclab dataset show datasets/step_error_surface1.h5");

  std::string toolpath;
  std::filesystem::path gcode_output;
  auto* gcode = app.add_subcommand("gcode", "Write a tool path as an ISO 6983 (G-code) program");
  gcode->add_option("toolpath", toolpath, "Tool path type: trochoid")->required();
  gcode->add_option("config", experiment, "Tool path YAML (kind: gcode)")
      ->required()
      ->check(CLI::ExistingFile);
  gcode->add_option("overrides", overrides, "Config overrides key=value");
  gcode->add_option("-o,--output", gcode_output, "G-code file to write (atomically)")->required();
  gcode->footer(
      "Example:\n  cnclab gcode trochoid experiments/trochoid/groove_table2.yaml -o groove.nc");

  std::string table;
  cnclab::TablesOptions tables_options;
  auto* tables = app.add_subcommand(
      "tables", "Print a paper's tables from result files beside the paper's numbers");
  tables->add_option("table", table, "Table name (none: list the tables)");
  tables->add_option("--results", tables_options.results_dir, "Results folder")
      ->capture_default_str();
  tables->add_option("--experiments", tables_options.experiments_dir, "Experiments folder")
      ->capture_default_str();
  tables->add_option("--reference", tables_options.reference_dir, "Paper numbers folder")
      ->capture_default_str();
  tables->add_option("--configs", tables_options.configs_dir, "Configs folder (study manifests)")
      ->capture_default_str();
  std::string tables_format = "text";
  tables->add_option("--format", tables_format, "Output: text (aligned), md, csv or latex")
      ->capture_default_str();
  tables->add_option("--profile", tables_options.profile,
                     "Tables of the results made with this profile (reproduce --quick: quick)");
  tables->footer(
      "Examples:\n  cnclab tables ik    # seed 004 Table 5 and the machine-space error\n"
      "  cnclab tables step-error --format md   # seed 000 Tables 2-8 as Markdown");

  std::string schema_kind;
  auto* schema = app.add_subcommand(
      "schema", "Print the JSON Schema (draft 2020-12) of experiment files, for editors");
  schema->add_option("--kind", schema_kind, "Only this kind's schema (train, sweep, ...)");
  schema->footer(
      "Example:\n  cnclab schema > cnclab.schema.json\n  then start an experiment file with\n"
      "  # yaml-language-server: $schema=../../cnclab.schema.json");

  auto* version = app.add_subcommand("version", "Print version, git commit and library versions");
  version->footer("Example:\n  cnclab version");

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --help-all
    // Every usage error in one form (a missing experiment file included):
    // "cnclab: error: experiment: File does not exist: x.yaml", exit 2.
    std::cerr << "cnclab: error: " << e.what() << " (--help explains the command)\n";
    return kExitUsage;
  }
  if (quick) {
    if (!common.profile.empty() && common.profile != "quick") {
      std::cerr << "error: --quick and --profile " << common.profile << " contradict\n";
      return kExitUsage;
    }
    common.profile = "quick";
  }
  // With a profile, results go to results/<profile> unless --out/--results
  // says otherwise: quick results never mix with the full ones.
  const auto profile_dir = [](CLI::App* sub, const char* option, const std::string& profile,
                              std::filesystem::path& dir) {
    if (sub->parsed() && !profile.empty() && sub->get_option(option)->count() == 0) {
      dir = dir / profile;
    }
  };
  profile_dir(run, "--out", common.profile, common.results_dir);
  profile_dir(reproduce, "--out", common.profile, common.results_dir);
  profile_dir(sweep, "--out", sweep_options.common.profile, sweep_options.common.results_dir);
  profile_dir(tables, "--results", tables_options.profile, tables_options.results_dir);

  try {
    const auto seed_option = [](const std::optional<std::string>& text,
                                const char* option) -> std::optional<std::uint64_t> {
      if (!text) return std::nullopt;
      return cnclab::parse_seed(*text, option);
    };
    const std::optional<std::uint64_t> seed = seed_option(seed_text, "--seed");
    sweep_options.sweep_seed = seed_option(sweep_seed_text, "--sweep-seed");
    if (*run) return cnclab::run_command(experiment, overrides, seed, common, std::cout, std::cerr);
    if (*validate) return cnclab::validate_command(experiment, overrides, seed, common, std::cout);
    if (*show) return cnclab::show_command(paths, std::cout);
    if (*schema) return cnclab::schema_command(schema_kind, std::cout);
    if (*reproduce) return cnclab::reproduce_command(paths, common, std::cout, std::cerr);
    if (*compare) return cnclab::compare_command(paths, compare_format, std::cout);
    if (*merge) return cnclab::sweep_merge_command(merge_dir, std::cout);
    if (*sweep) {
      if (experiment.empty()) throw cnclab::ConfigError("sweep: an experiment file is required");
      return cnclab::sweep_command(experiment, sweep_words, seed, sweep_options, std::cout,
                                   std::cerr);
    }
    if (*generate) {
      return cnclab::dataset_generate_command(
          experiment, overrides,
          dataset_out ? std::optional<std::filesystem::path>(*dataset_out) : std::nullopt,
          dataset_quiet ? cnclab::ProgressMode::quiet : cnclab::ProgressMode::automatic, std::cout,
          std::cerr);
    }
    if (*dataset_show) return cnclab::dataset_show_command(experiment, std::cout);
    if (*gcode) {
      return cnclab::gcode_command(toolpath, experiment, gcode_output, overrides, std::cout);
    }
    if (*tables) {
      tables_options.format = cnclab::parse_table_format(tables_format);
      return cnclab::tables_command(table, tables_options, std::cout);
    }
    if (*version) return cnclab::version_command(std::cout);
  } catch (const cnclab::ConfigError& e) {
    std::cerr << "cnclab: error: " << e.what() << "\n";
    return kExitUsage;
  } catch (const cnclab::Error& e) {
    std::cerr << "cnclab: error: " << e.what() << "\n";
    return kExitFailed;
  } catch (const std::exception& e) {
    std::cerr << "cnclab: internal error: " << e.what() << "\n";
    return kExitFailed;
  }
  return kExitUsage;
}
