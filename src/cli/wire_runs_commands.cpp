// CLI11 wiring of runs (cli_wiring.hpp); the bodies live in report/.
#include <iostream>
#include <memory>

#include "cli/cli_wiring.hpp"
#include "cnclab/pipeline/reproduce_inputs.hpp"
#include "cnclab/report/garbage.hpp"
#include "cnclab/report/html_report.hpp"
#include "cnclab/report/runs_command.hpp"

namespace cnclab {

namespace {

void add_runs(CLI::App& app, CommandAction& action) {
  auto o = std::make_shared<RunsOptions>();
  auto* runs = app.add_subcommand(
      "runs", "List results: status, the config keys that vary among them, metrics with units");
  runs->add_option("folders", o->folders,
                   "Result files or folders, searched recursively (default: the results root)");
  runs->add_option("--results", o->results_dir,
                   "The results root; its index file .runs-index.json makes listing fast")
      ->capture_default_str();
  runs->add_option("--where", o->where,
                   "KEY OP VALUE (OP: = != < <= > >= ~ contains), as one word or three; KEY is "
                   "a metric, a config key, its last dotted part(s), or file, experiment, kind, "
                   "status, profile, host, start_utc, wall_seconds, cpu_seconds, "
                   "project_commit, project_dirty, config_hash; repeat for AND")
      ->expected(1, 3)
      ->allow_extra_args(false);
  runs->add_option("--sort", o->sort, "Sort by KEY (ascending; -KEY descending; missing last)");
  runs->add_option("--columns", o->columns,
                   "Comma-separated KEYs to show after the file (default: experiment, status, "
                   "varying config keys, metrics)");
  runs->add_option("--format", o->format, "table, md, csv or json")->capture_default_str();
  runs->add_option("--diff", o->diff,
                   "Two result files: only the config keys that differ and "
                   "the metric deltas (as compare)")
      ->expected(2);
  runs->add_flag("--no-index", o->no_index, "Read every file; do not read or write the index");
  runs->add_flag("--full", o->full, "--diff: arrays in full");
  runs->footer(
      "Examples:\n  cnclab runs\n"
      "  cnclab runs results/step_error --where 'surface = 2' --where 'keep >= 0.8' --sort "
      "validation.rmse\n"
      "  cnclab runs --format csv > runs.csv\n"
      "  cnclab runs --diff results/a/a-seed1-1a2b3c4d.h5 results/a/a-seed2-5e6f7a8b.h5\n"
      "The index is refreshed from each file's size and modification time and never "
      "trusted over the files.");
  runs->callback([o, &action] { action = [o] { return runs_command(*o, std::cout, std::cerr); }; });
}

struct GcArgs {
  std::vector<std::string> folders;
  GcOptions options;
  bool dry_run = false;
};

void add_gc(CLI::App& app, CommandAction& action) {
  auto a = std::make_shared<GcArgs>();
  auto* gc = app.add_subcommand(
      "gc", "List (default) or remove results and datasets that no experiment still produces");
  gc->add_option("folders", a->folders, "Experiment files or folders (default: experiments)");
  add_store_options(*gc, a->options.results_dir, a->options.datasets_dir);
  auto* dry = gc->add_flag("--dry-run", a->dry_run, "List only (the default)");
  gc->add_flag("--yes", a->options.remove, "Remove what is listed")->excludes(dry);
  gc->footer(
      "Kept: results whose config an experiment file (with no profile or a profile named by a "
      "folder of the results root) still resolves to, sweeps of those experiments, and what "
      "they name (upstream results, outputs, datasets); datasets a current experiment reads. "
      "Files gc did not make are never touched.\n"
      "Examples:\n  cnclab gc                 # list\n  cnclab gc --yes           # remove");
  gc->callback([a, &action] {
    action = [a] {
      GcOptions o = a->options;
      o.experiments = find_experiments(a->folders);
      return gc_command(o, std::cout);
    };
  });
}

void add_report(CLI::App& app, CommandAction& action) {
  auto o = std::make_shared<ReportOptions>();
  auto* report = app.add_subcommand(
      "report", "One self-contained HTML file (offline, printable) of studies, sweeps or results");
  report
      ->add_option("inputs", o->inputs,
                   "Study names (as `cnclab tables`), sweep folders or "
                   "result files")
      ->required();
  report->add_option("-o,--output", o->output, "The .html file to write")->required();
  report->add_option("--results", o->tables.results_dir, kResultsRootHelp)->capture_default_str();
  add_profile_option(*report, o->tables.profile);
  report->footer(
      "Examples:\n  cnclab report step-error -o step-error.html\n"
      "  cnclab report results/narx/sweep-1a2b3c4d -o sweep.html\n"
      "  cnclab report results/friedman1_mlp/friedman1_mlp-seed42-*.h5 -o runs.html\n"
      "Tables beside the paper's numbers with the declared targets (PASS/FAIL), training "
      "histories and provenance as inline SVG and text: no script, no network request. Exit 1 "
      "when a declared target fails.");
  report->callback([report, o, &action] {
    apply_profile_dir(*report, "--results", o->tables.profile, o->tables.results_dir);
    action = [o] { return report_command(*o, std::cout); };
  });
}

}  // namespace

void add_runs_commands(CLI::App& app, CommandAction& action) {
  add_runs(app, action);
  add_gc(app, action);
  add_report(app, action);
}

}  // namespace cnclab
