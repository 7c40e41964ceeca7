#pragma once
// What a command's options mean for the runner, and a result's metrics as
// the commands print them on one line.
#include <map>
#include <ostream>
#include <string>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/experiment/runner.hpp"

namespace cnclab {

// The runner options a command's options imply (progress and notes to `log`
// unless quiet).
RunOptions run_options(const CommandOptions& options, std::ostream& log);
// A result's metrics on one line, grouped by split: "train: mse 1.2, rmse
// 1.1; validation: ...; test: ..." (names without a split last, whole).
std::string metrics_line(const std::map<std::string, double>& metrics);

}  // namespace cnclab
