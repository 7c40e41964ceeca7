#pragma once
// `cnclab init DIR`: a project folder from cnclab's template
// (SHARE/templates/project, core/share_paths.hpp): experiments/ with a
// starter experiment per study, configs/ (a project's configs override the
// installed ones), datasets/, results/, a README and a .gitignore.
#include <filesystem>
#include <ostream>

namespace cnclab {

struct InitOptions {
  std::filesystem::path dir;  // the project folder, created with its parents
  // Also into a folder that is not empty: every existing file is kept (a
  // template file of the same name is then not copied, and listed).
  bool force = false;
};

// Creates the project; ConfigError (exit 2) when options.dir is a file, or a
// non-empty folder without force; IoError when it cannot be written.
// Returns 0.
int init_command(const InitOptions& options, std::ostream& out);

}  // namespace cnclab
