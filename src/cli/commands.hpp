#pragma once
// The CLI's command bodies (main.cpp wires arguments to them).
// Each returns the exit code: 0 ok, 1 run failed; bad configuration throws
// ConfigError (exit 2), other problems cnclab::Error (exit 1).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/experiment/job_kinds.hpp"

namespace cnclab {

int run_command(const std::filesystem::path& experiment, const std::vector<std::string>& overrides,
                std::optional<std::uint64_t> seed, const CommandOptions& options, std::ostream& out,
                std::ostream& log);
int validate_command(const std::filesystem::path& experiment,
                     const std::vector<std::string>& overrides, std::optional<std::uint64_t> seed,
                     const CommandOptions& options, std::ostream& out);
// Result files (print_result) and sweep summaries (summary.h5: the ranking as
// `cnclab sweep merge` prints it, read from the file alone; nothing written).
// options.full: configs with every array in full.
int show_command(const std::vector<std::string>& result_files, const CommandOptions& options,
                 std::ostream& out);
// Runs the experiments under `paths` and the ones they need, upstream first
// (experiment_graph.hpp); reuses every result whose resolved config and
// upstream results are unchanged; prints per experiment ran/reused and why.
int reproduce_command(const std::vector<std::string>& paths, const CommandOptions& options,
                      std::ostream& out, std::ostream& log);
// What reproduce runs from `paths`: training experiments (the graph) and
// `kind: <job>` files (job_kinds.hpp, after the graph); a file whose kind
// cannot be read stays in the graph, to be reported there.
struct ReproduceInputs {
  std::vector<std::filesystem::path> files;
  std::vector<std::pair<std::filesystem::path, JobKind>> jobs;
  // The files found under `paths` that do not define the profile (they run
  // with their own settings; experiment/profiles.hpp): one line, or "".
  std::string profile_note;
};
// The experiment files under `paths` split into training experiments and
// `kind:` jobs; the training experiments a job reads (JobKind::upstream,
// loaded with `profile`) are added to the training files once. ConfigError
// when no file found defines `profile` (the set rule of profiles.hpp).
ReproduceInputs reproduce_inputs(const std::vector<std::string>& paths, const std::string& profile);

int version_command(std::ostream& out);
// `cnclab gcode trochoid CONFIG.yaml -o FILE.nc`: the tool path of a `kind:
// gcode` file written atomically to `output`, its report printed.
int gcode_command(const std::string& toolpath, const std::filesystem::path& config,
                  const std::filesystem::path& output, const std::vector<std::string>& overrides,
                  std::ostream& out);

// The runner options a command's options imply (progress and notes to `log`
// unless quiet).
struct RunOptions;
RunOptions run_options(const CommandOptions& options, std::ostream& log);
// A result's metrics on one line, grouped by split: "train: mse 1.2, rmse
// 1.1; validation: ...; test: ..." (names without a split last, whole).
std::string metrics_line(const std::map<std::string, double>& metrics);

// Experiment YAML files under `paths` (files as given, folders recursively),
// sorted; a missing path is a ConfigError. A folder below a given one that
// holds a file kOptInMarker is an opt-in set (a study too long for
// `reproduce` of everything, README command 1): skipped unless it is
// itself given (or a folder or file inside it).
inline constexpr const char* kOptInMarker = "OPT_IN.md";
std::vector<std::filesystem::path> find_experiments(const std::vector<std::string>& paths);

}  // namespace cnclab
