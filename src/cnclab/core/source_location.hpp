#pragma once
#include <string>

namespace cnclab {

// Where a config value came from: a YAML file position (1-based line and
// column) or a command-line override ("override trainer.momentum=1.5").
struct SourceLocation {
  std::string file;
  int line = 0;  // 0 = unknown / not a file position
  int column = 0;

  // "file:line:col", or just "file" when the position is unknown.
  std::string str() const {
    if (line <= 0) return file;
    return file + ":" + std::to_string(line) + ":" + std::to_string(column);
  }
};

}  // namespace cnclab
