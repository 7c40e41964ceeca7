#pragma once
// Option keys that take a map inline or the name of a YAML file holding it
// (dataset.options.surface: configs/surfaces/surface1.yaml, machine:
// configs/machines/biaxial_router.yaml).
#include <filesystem>
#include <string>

#include "cnclab/core/config.hpp"

namespace cnclab {

// The file a scalar `key` names: resolved like include: from the file that
// gives it (core/config.hpp lookup_config_path); from a command-line override
// (no file position) relative to the working directory. A name found nowhere
// fails on the key (ConfigError at its position).
std::filesystem::path named_config_file(const ConfigReader& r, const std::string& key);

}  // namespace cnclab
