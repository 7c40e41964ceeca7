// CLI11 wiring of dataset generate/show, gcode, tables, schema, version and
// init (cli_wiring.hpp).
#include <iostream>
#include <memory>
#include <vector>

#include "cli/cli_wiring.hpp"
#include "cli/commands.hpp"
#include "cnclab/data/dataset_commands.hpp"
#include "cnclab/experiment/experiment_schema.hpp"
#include "cnclab/pipeline/project_init.hpp"
#include "cnclab/report/tables.hpp"
#include "cnclab/sweep/slurm_fields.hpp"
#include "cnclab/sweep/sweep_fields.hpp"

namespace cnclab {
namespace {

struct GenerateArgs {
  std::string config;
  std::vector<std::string> overrides;
  std::optional<std::string> out;
  bool quiet = false;
};

void add_dataset(CLI::App& app, CommandAction& action) {
  auto* dataset = app.add_subcommand("dataset", "Generate or inspect a dataset file");
  dataset->require_subcommand(1);
  dataset->footer(
      "Example:\n  cnclab dataset generate configs/datasets/step_error_surface1.yaml\n  cnclab "
      "dataset show datasets/step_error_surface1.h5");
  auto g = std::make_shared<GenerateArgs>();
  auto* generate = dataset->add_subcommand(
      "generate",
      "Generate the dataset a YAML `dataset:` section describes; writes HDF5 atomically");
  generate->add_option("config", g->config, "YAML file with a dataset section")
      ->required()
      ->check(CLI::ExistingFile);
  generate->add_option("overrides", g->overrides, "Config overrides key=value");
  generate->add_option("--out", g->out, "Output file (default datasets/<config stem>.h5)");
  add_quiet_flag(*generate, g->quiet);
  generate->footer(
      "Example:\n  cnclab dataset generate configs/datasets/step_error_surface1.yaml\n  cnclab "
      "dataset generate configs/datasets/step_error_surface2.yaml dataset.options.lines=20 "
      "--out s2.h5");
  generate->callback([g, &action] {
    action = [g] {
      return dataset_generate_command(
          g->config, g->overrides,
          g->out ? std::optional<std::filesystem::path>(*g->out) : std::nullopt,
          g->quiet ? ProgressMode::quiet : ProgressMode::automatic, std::cout, std::cerr);
    };
  });
  auto file = std::make_shared<std::string>();
  auto* show = dataset->add_subcommand(
      "show", "Print a dataset file: counts, ranges with units, histogram, convex/concave split");
  show->add_option("file", *file, "Dataset HDF5 file")->required()->check(CLI::ExistingFile);
  show->footer("Example:\n  cnclab dataset show datasets/step_error_surface1.h5");
  show->callback(
      [file, &action] { action = [file] { return dataset_show_command(*file, std::cout); }; });
}

struct GcodeArgs {
  std::string toolpath, config;
  std::vector<std::string> overrides;
  std::filesystem::path output;
};

void add_gcode(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<GcodeArgs>();
  auto* gcode = app.add_subcommand("gcode", "Write a tool path as an ISO 6983 (G-code) program");
  gcode->add_option("toolpath", a->toolpath, "Tool path type: trochoid")->required();
  gcode->add_option("config", a->config, "Tool path YAML (kind: gcode)")
      ->required()
      ->check(CLI::ExistingFile);
  gcode->add_option("overrides", a->overrides, "Config overrides key=value");
  gcode->add_option("-o,--output", a->output, "G-code file to write (atomically)")->required();
  gcode->footer(
      "Example:\n  cnclab gcode trochoid experiments/trochoid/groove_table2.yaml -o groove.nc");
  gcode->callback([a, &action] {
    action = [a] {
      return gcode_command(a->toolpath, a->config, a->output, a->overrides, std::cout);
    };
  });
}

struct TablesArgs {
  std::string table;
  TablesOptions options;
  std::string format = "text";
};

void add_tables(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<TablesArgs>();
  auto* tables = app.add_subcommand(
      "tables", "Print a paper's tables from result files beside the paper's numbers");
  tables->add_option("table", a->table, "Table name (none: list the tables)");
  tables->add_option("--results", a->options.results_dir, kResultsRootHelp)
      ->capture_default_str()
      ->check(CLI::ExistingDirectory);
  tables
      ->add_option("--experiments", a->options.experiments_dir,
                   "Experiments folder (default: ./experiments, else the installed ones)")
      ->check(CLI::ExistingDirectory);
  tables
      ->add_option("--reference", a->options.reference_dir,
                   "Paper numbers folder (default: ./results/reference, else the installed)")
      ->check(CLI::ExistingDirectory);
  tables
      ->add_option("--configs", a->options.configs_dir,
                   "Configs folder, study manifests (default: ./configs, else the installed)")
      ->check(CLI::ExistingDirectory);
  tables
      ->add_option("--format", a->format,
                   "Output: text (aligned), md, latex for people; csv, json numbers only "
                   "(mean ± std as _mean and _std columns, units in the column names)")
      ->capture_default_str();
  tables->add_flag("--check", a->options.check,
                   "After the tables, each declared target of the study's manifest "
                   "(configs/studies/*.yaml targets:) with its measured value and PASS/FAIL; "
                   "exit 1 on any FAIL");
  add_profile_option(*tables, a->options.profile);
  tables->footer(
      "Examples:\n  cnclab tables ik    # seed 004 Table 5 and the machine-space error\n"
      "  cnclab tables step-error --format md   # seed 000 Tables 2-8 as Markdown\n"
      "  cnclab tables step-error --check       # and its targets, PASS/FAIL (exit 1 on a FAIL)\n"
      "  cnclab tables contour-error --profile quick --format csv   # results/quick, numbers only");
  tables->callback([tables, a, &action] {
    apply_profile_dir(*tables, "--results", a->options.profile, a->options.results_dir);
    action = [a] {
      a->options.format = parse_table_format(a->format);
      return tables_command(a->table, a->options, std::cout);
    };
  });
}

}  // namespace

void add_tool_commands(CLI::App& app, CommandAction& action) {
  add_dataset(app, action);
  add_gcode(app, action);
  add_tables(app, action);
  auto schema_kind = std::make_shared<std::string>();
  auto* schema = app.add_subcommand(
      "schema", "Print the JSON Schema (draft 2020-12) of experiment files, for editors");
  schema->add_option("--kind", *schema_kind, "Only this kind's schema (train, sweep, ...)");
  schema->footer(
      "Example:\n  cnclab schema > cnclab.schema.json\n  then start an experiment file with\n"
      "  # yaml-language-server: $schema=../../cnclab.schema.json");
  schema->callback([schema_kind, &action] {
    action = [schema_kind] {
      std::cout << experiment_file_schema(*schema_kind, sweep_fields().info(),
                                          slurm_fields().info())
                       .dump(2)
                << "\n";
      return 0;
    };
  });
  auto* version = app.add_subcommand("version", "Print version, git commit and library versions");
  version->footer("Example:\n  cnclab version");
  version->callback([&action] { action = [] { return version_command(std::cout); }; });
}

void add_init_command(CLI::App& app, CommandAction& action) {
  auto options = std::make_shared<InitOptions>();
  auto* init = app.add_subcommand(
      "init",
      "Create a project folder: starter experiments per study, configs/, datasets/, "
      "results/, README, .gitignore");
  init->add_option("dir", options->dir, "Project folder (new or empty; created)")->required();
  init->add_flag("--force", options->force,
                 "Also into a non-empty folder; existing files are kept, never overwritten");
  init->footer(
      "Example:\n  cnclab init ~/studies/mill && cd ~/studies/mill && cnclab reproduce --quick\n"
      "The project's configs/ come first for `include: configs/...`, then cnclab's installed "
      "configs (`cnclab version` prints where they are).");
  init->callback(
      [options, &action] { action = [options] { return init_command(*options, std::cout); }; });
}

}  // namespace cnclab
