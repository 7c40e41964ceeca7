#pragma once
// The short command bodies that only call the library and print (the
// wire_*.cpp files wire arguments to them; the other bodies live in their
// modules). Each returns the exit code: 0 ok, 1 run failed; bad
// configuration throws ConfigError (exit 2), other problems cnclab::Error
// (exit 1).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"

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
int version_command(std::ostream& out);
// `cnclab gcode trochoid CONFIG.yaml -o FILE.nc`: the tool path of a `kind:
// gcode` file written atomically to `output`, its report printed.
int gcode_command(const std::string& toolpath, const std::filesystem::path& config,
                  const std::filesystem::path& output, const std::vector<std::string>& overrides,
                  std::ostream& out);

}  // namespace cnclab
