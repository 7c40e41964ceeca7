#pragma once
// Small helpers shared by the experiment-spec readers and writers.
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"

namespace cnclab {

// "must be one of: a, b, c"
std::string one_of(const std::vector<std::string>& names);
// r[key] (default `fallback`), which must be one of `allowed`.
std::string choice(const ConfigReader& r, const std::string& key, const std::string& fallback,
                   const std::vector<std::string>& allowed);

}  // namespace cnclab
