#pragma once
// The CLI's commands as library functions (src/cli only wires arguments).
// Each returns the exit code: 0 ok, 1 run failed; bad configuration throws
// ConfigError (exit 2), other problems cnclab::Error (exit 1).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

namespace cnclab {

struct CommandOptions {
  std::filesystem::path results_dir = "results";
  std::filesystem::path datasets_dir = "datasets";
  bool quiet = false;
};

int run_command(const std::filesystem::path& experiment, const std::vector<std::string>& overrides,
                std::optional<std::uint64_t> seed, const CommandOptions& options, std::ostream& out,
                std::ostream& log);
int validate_command(const std::filesystem::path& experiment,
                     const std::vector<std::string>& overrides, std::optional<std::uint64_t> seed,
                     std::ostream& out);
int show_command(const std::vector<std::string>& result_files, std::ostream& out);
int reproduce_command(const std::vector<std::string>& paths, const CommandOptions& options,
                      std::ostream& out, std::ostream& log);
int version_command(std::ostream& out);
// `cnclab gcode trochoid CONFIG.yaml -o FILE.nc`: the tool path of a `kind:
// gcode` file written atomically to `output`, its report printed.
int gcode_command(const std::string& toolpath, const std::filesystem::path& config,
                  const std::filesystem::path& output, const std::vector<std::string>& overrides,
                  std::ostream& out);

// Experiment YAML files under `paths` (files as given, folders recursively),
// sorted; a missing path is a ConfigError.
std::vector<std::filesystem::path> find_experiments(const std::vector<std::string>& paths);

}  // namespace cnclab
