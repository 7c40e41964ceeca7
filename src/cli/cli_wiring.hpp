#pragma once
// CLI11 wiring of the subcommands, one function per group. Each add_*
// function declares a subcommand's options and, once that subcommand is
// parsed, sets `action` to the call of its command body (src/cli/*.hpp);
// main() runs the action and maps exceptions to exit codes.
#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

namespace cnclab {

using CommandAction = std::function<int()>;

// run, validate, show, reproduce, compare (wire_experiment_commands.cpp).
void add_experiment_commands(CLI::App& app, CommandAction& action);
// sweep, sweep merge, sweep --slurm and status (wire_sweep_commands.cpp,
// wire_slurm_commands.cpp).
void add_sweep_commands(CLI::App& app, CommandAction& action);
// dataset generate/show, gcode, tables, schema, version (wire_tool_commands.cpp).
void add_tool_commands(CLI::App& app, CommandAction& action);
// surface show/export/example-part (wire_surface_commands.cpp).
void add_surface_commands(CLI::App& app, CommandAction& action);
// predict, export (wire_deploy_commands.cpp).
void add_deploy_commands(CLI::App& app, CommandAction& action);
// runs, gc, report (wire_runs_commands.cpp).
void add_runs_commands(CLI::App& app, CommandAction& action);
// init (wire_tool_commands.cpp).
void add_init_command(CLI::App& app, CommandAction& action);

// Shared by the wiring files (cli_wiring.cpp).
// --out / --results: the results root (results_folder, result_store.hpp).
extern const char* const kResultsRootHelp;
// Counts (--jobs, --repeats, --trials): digits only. CLI11 alone reads "-1"
// for an unsigned option as 2^64 - 1 (a sweep then plans forever).
const CLI::Validator& count_validator();
// A seed option read as text (CLI11 would turn "-1" into 2^64 - 1, and its
// own errors do not take our error form): ConfigError naming `option`.
std::optional<std::uint64_t> seed_option(const std::optional<std::string>& text,
                                         const char* option);
// `dir` (the root, from `option`: --out or --results) becomes the results
// folder of `profile`: ROOT/profile (results_folder, result_store.hpp, with
// its note for a folder in the old layout on stderr). Quick results never
// mix with the full ones.
void apply_profile_dir(const CLI::App& sub, const char* option, const std::string& profile,
                       std::filesystem::path& dir);

// The options several commands share, each said the same way everywhere:
// --out ROOT (kResultsRootHelp) and --data-dir DIR, their defaults shown.
void add_store_options(CLI::App& sub, std::filesystem::path& results_dir,
                       std::filesystem::path& datasets_dir);
// --quiet, -q: no progress output.
void add_quiet_flag(CLI::App& sub, bool& quiet);
// --profile NAME (kProfileHelp).
void add_profile_option(CLI::App& sub, std::string& profile);
// --seed UINT read as text (seed_option).
void add_seed_option(CLI::App& sub, std::optional<std::string>& seed_text);

}  // namespace cnclab
