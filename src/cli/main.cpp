// cnclab command line: CLI11 wiring only (cli_wiring.hpp); the work is in
// the library. Exit codes (the README's table): 0 done; 1 a run, a trial or a
// target failed, a result it needs is not made yet, or a file could not be
// read or written (cnclab::Error); 2 usage, configuration or a missing input
// file or folder (cnclab::ConfigError, CLI11's errors: Existing* checks).
//
// `cnclab --parse-only COMMAND ...` (hidden) parses the command line and
// exits 0 without running the command, or 2 as any usage error: how the
// README's command lines are checked (tests/cli/readme_commands_test.py).
#include <CLI/CLI.hpp>
#include <iostream>

#include "cli/builtins.hpp"
#include "cli/cli_wiring.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/isa.hpp"

namespace {

constexpr int kExitFailed = 1;
constexpr int kExitUsage = 2;

}  // namespace

int main(int argc, char** argv) {
  cnclab::register_builtins();
  CLI::App app{
      "cnclab: experiments, datasets and paper tables for neural-network studies of CNC "
      "machining error.\n"
      "Example: cnclab run experiments/friedman/friedman1_mlp.yaml trainer.epochs=50"};
  app.require_subcommand(1);
  app.set_help_all_flag("--help-all", "Show help for every subcommand");
  app.footer(
      "Exit codes: 0 done; 1 a run, trial or target failed, a result it needs is not made yet, "
      "or a file could not be read or written; 2 usage, configuration or a missing input file "
      "or folder.");
  bool parse_only = false;
  app.add_flag("--parse-only", parse_only)->group("");  // hidden
  cnclab::CommandAction action;
  cnclab::add_experiment_commands(app, action);
  cnclab::add_sweep_commands(app, action);
  cnclab::add_tool_commands(app, action);
  cnclab::add_surface_commands(app, action);
  cnclab::add_deploy_commands(app, action);
  cnclab::add_runs_commands(app, action);
  cnclab::add_init_command(app, action);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --help-all
    // Every usage error in one form (a missing experiment file included):
    // "cnclab: error: experiment: File does not exist: x.yaml", exit 2.
    std::cerr << "cnclab: error: " << e.what() << " (--help explains the command)\n";
    return kExitUsage;
  }
  if (!action) return kExitUsage;
  if (parse_only) return 0;
  try {
    cnclab::active_isa();  // CNCLAB_ISA that cannot be honoured: exit 2 before any work
    return action();
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
}
