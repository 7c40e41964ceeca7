#pragma once
// `cnclab schema [--kind K]`: the JSON Schema (draft 2020-12) of experiment
// files, from the field declarations (cnclab/experiment/experiment_schema.hpp).
#include <ostream>
#include <string>

namespace cnclab {

// Prints the schema (all kinds, or kind `kind` alone) as indented JSON.
// ConfigError for an unknown kind.
int schema_command(const std::string& kind, std::ostream& out);

}  // namespace cnclab
