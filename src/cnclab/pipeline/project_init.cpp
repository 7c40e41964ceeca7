#include "cnclab/pipeline/project_init.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/share_paths.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// "a, b, c and 4 more": the first entries of a non-empty folder, for the message.
std::string init_listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(dir)) {
    names.push_back(entry.path().filename().string());
  }
  std::sort(names.begin(), names.end());
  constexpr std::size_t kShown = 3;
  std::string text;
  for (std::size_t i = 0; i < std::min(names.size(), kShown); ++i) {
    text += (i == 0 ? "" : ", ") + names[i];
  }
  if (names.size() > kShown) text += " and " + std::to_string(names.size() - kShown) + " more";
  return text;
}

// The template's files relative to its root, sorted (folders included,
// each before its contents).
std::vector<fs::path> init_template_entries(const fs::path& root) {
  std::vector<fs::path> out;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    out.push_back(entry.path().lexically_relative(root));
  }
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

int init_command(const InitOptions& options, std::ostream& out) {
  const fs::path& dir = options.dir;
  if (dir.empty()) throw ConfigError("init: DIR must not be empty");
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec)) {
    throw ConfigError("init: " + dir.string() + " exists and is not a folder");
  }
  if (fs::is_directory(dir, ec) && !fs::is_empty(dir, ec) && !options.force) {
    throw ConfigError("init: " + dir.string() + " is not empty (" + init_listing(dir) +
                      "); choose a new or empty folder, or add --force to add the project "
                      "files there (existing files are kept)");
  }
  const fs::path source = require_installed("templates/project");
  std::vector<fs::path> created, kept;
  try {
    fs::create_directories(dir);
    for (const fs::path& rel : init_template_entries(source)) {
      const fs::path target = dir / rel;
      if (fs::is_directory(source / rel)) {
        fs::create_directories(target);
      } else if (fs::exists(target)) {
        kept.push_back(rel);
      } else {
        fs::copy_file(source / rel, target);
        created.push_back(rel);
      }
    }
    // Empty in the template (git keeps no empty folder): made here.
    for (const char* folder : {"datasets", "results"}) fs::create_directories(dir / folder);
  } catch (const fs::filesystem_error& e) {
    throw IoError("init: " + dir.string() + ": " + e.what());
  }
  out << "cnclab init: " << dir.string() << ": " << created.size() << " file(s) from "
      << source.string() << "\n";
  for (const auto& rel : created) out << "  " << rel.string() << "\n";
  for (const auto& rel : kept) out << "  " << rel.string() << " (exists: kept)\n";
  out << "Next:\n  cd " << dir.string() << " && cnclab reproduce --quick\n";
  return 0;
}

}  // namespace cnclab
