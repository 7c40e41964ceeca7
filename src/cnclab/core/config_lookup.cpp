// Where a file named in a config file is searched (ConfigSearch,
// lookup_config_path); see config.hpp for the order.
#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "cnclab/core/config.hpp"

namespace cnclab {
namespace fs = std::filesystem;

ConfigSearch ConfigSearch::from_environment() {
  ConfigSearch search;
  if (const char* value = std::getenv("CNCLAB_CONFIG_PATH")) {
    std::istringstream entries{std::string(value)};
    for (std::string entry; std::getline(entries, entry, ':');) {
      if (!entry.empty()) search.config_path.emplace_back(entry);
    }
  }
  std::error_code ec;
  search.current_dir = fs::current_path(ec);  // "" (none) if it was removed
  search.shared = installed_share_roots();
  return search;
}

ConfigLookup lookup_config_path(const fs::path& naming_file, const std::string& name,
                                const ConfigSearch& search) {
  ConfigLookup out;
  std::error_code ec;
  std::vector<fs::path> seen;  // absolute, normalised: each candidate once
  const auto consider = [&](const fs::path& candidate, const std::string& why) {
    fs::path key = fs::weakly_canonical(candidate, ec);
    if (ec) key = fs::absolute(candidate, ec).lexically_normal();
    if (std::find(seen.begin(), seen.end(), key) != seen.end()) return false;
    seen.push_back(key);
    out.tried.emplace_back(candidate, why);
    if (fs::exists(candidate, ec)) out.found = candidate;
    return out.found.has_value();
  };
  if (consider(naming_file.parent_path() / name, "relative to the naming file")) return out;

  // Only "configs/REST" names a file in a configs folder.
  const fs::path relative(name), configs("configs");
  if (relative.is_absolute() || relative.empty() || *relative.begin() != configs) return out;
  const fs::path rest = relative.lexically_relative(configs);
  if (rest.empty() || rest == ".") return out;

  bool any_ancestor = false;
  const fs::path start = fs::absolute(naming_file, ec).parent_path();
  for (fs::path dir = start; !dir.empty(); dir = dir.parent_path()) {
    if (fs::is_directory(dir / configs, ec)) {
      any_ancestor = true;
      if (consider(dir / configs / rest, "configs/ of an enclosing folder")) return out;
    }
    if (dir == dir.parent_path()) break;
  }
  if (!any_ancestor) out.notes.push_back("no folder from " + start.string() + " up has configs/");

  for (const auto& entry : search.config_path) {
    if (consider(entry / rest, "CNCLAB_CONFIG_PATH")) return out;
  }
  if (search.config_path.empty()) {
    out.notes.push_back(
        "CNCLAB_CONFIG_PATH (':'-separated folders laid out like configs/) is not set");
  }
  if (!search.current_dir.empty() &&
      consider(search.current_dir / configs / rest, "configs/ of the current directory")) {
    return out;
  }
  for (const auto& root : search.shared.roots) {
    if (consider(root.dir / configs / rest, "cnclab's configs, " + root.why)) return out;
  }
  if (search.shared.roots.empty() && !search.shared.absent.empty()) {
    out.notes.push_back(search.shared.none_note());
  }
  return out;
}

std::string ConfigLookup::not_found_message() const {
  std::string text = "not found; looked in:";
  for (std::size_t i = 0; i < tried.size(); ++i) {
    text += (i == 0 ? " " : ", ") + tried[i].first.string() + " (" + tried[i].second + ")";
  }
  for (const auto& note : notes) text += "; " + note;
  return text;
}

fs::path resolve_config_path(const fs::path& naming_file, const std::string& name,
                             const ConfigSearch& search) {
  ConfigLookup lookup = lookup_config_path(naming_file, name, search);
  return lookup.found ? *lookup.found : lookup.tried.front().first;
}

}  // namespace cnclab
