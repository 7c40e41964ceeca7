#pragma once
// `cnclab sweep` and `cnclab sweep merge` (exit codes: 0 done, 1 a trial
// failed; an interrupted sweep returns 128 + the signal number).
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/pipeline/sweep_prepare.hpp"

namespace cnclab {

// `words`: key=value overrides and key=v1,v2 / key=fn(...) sweep parameters.
int sweep_command(const std::filesystem::path& experiment, const std::vector<std::string>& words,
                  std::optional<std::uint64_t> seed, const SweepCommandOptions& options,
                  std::ostream& out, std::ostream& log);

// Builds summary.h5 of a sweep folder from the trial files there (after
// shards ran). Exit 0 if every trial completed, 1 if some failed or are
// missing (listed).
int sweep_merge_command(const std::filesystem::path& dir, std::ostream& out);

}  // namespace cnclab
