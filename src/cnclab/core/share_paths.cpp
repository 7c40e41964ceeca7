// cnclab's share roots and the search of a shared file (share_paths.hpp).
#include "cnclab/core/share_paths.hpp"

#include <algorithm>

#include "cnclab/core/error.hpp"

// Set for this file only by src/cnclab/core/CMakeLists.txt.
#ifndef CNCLAB_SHARE_DIR
#define CNCLAB_SHARE_DIR ""
#endif
#ifndef CNCLAB_SHARE_SOURCE_DIR
#define CNCLAB_SHARE_SOURCE_DIR ""
#endif
#ifndef CNCLAB_SHARE_BUILD_DIR
#define CNCLAB_SHARE_BUILD_DIR ""
#endif

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// `dir` normalised for comparison (canonical when it exists).
fs::path share_key(const fs::path& dir) {
  std::error_code ec;
  fs::path key = fs::weakly_canonical(dir, ec);
  return ec ? dir.lexically_normal() : key;
}

// Whether `file` lies inside folder `dir` (both canonical).
bool share_is_inside(const fs::path& file, const fs::path& dir) {
  const fs::path rel = file.lexically_relative(dir);
  return !rel.empty() && *rel.begin() != "..";
}

void share_add(ShareRoots& out, const fs::path& dir, const std::string& why) {
  if (dir.empty()) return;
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    out.absent.push_back(why + " " + dir.string() + ": absent");
    return;
  }
  const fs::path key = share_key(dir);
  const bool seen = std::any_of(out.roots.begin(), out.roots.end(),
                                [&](const ShareRoot& r) { return share_key(r.dir) == key; });
  if (!seen) out.roots.push_back({dir.lexically_normal(), why});
}

}  // namespace

ShareRoots share_roots_for(const fs::path& executable) {
  ShareRoots out;
  const fs::path exe = share_key(executable);
  if (!executable.empty()) {
    share_add(out, exe.parent_path().parent_path() / "share" / "cnclab",
              "installed, next to the executable");
  }
  share_add(out, CNCLAB_SHARE_DIR, "install folder compiled in");
  const fs::path build(CNCLAB_SHARE_BUILD_DIR);
  if (!build.empty() && !executable.empty() && share_is_inside(exe, share_key(build))) {
    share_add(out, CNCLAB_SHARE_SOURCE_DIR, "source tree of this build");
  }
  return out;
}

ShareRoots installed_share_roots() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return share_roots_for(ec ? fs::path() : exe);
}

std::string ShareRoots::none_note() const {
  std::string text = "no cnclab share folder";
  for (std::size_t i = 0; i < absent.size(); ++i) text += (i == 0 ? " (" : ", ") + absent[i];
  return text + (absent.empty() ? "" : ")");
}

ShareLookup find_shared(const fs::path& relative, bool in_project, const ShareRoots& roots) {
  ShareLookup out;
  std::error_code ec;
  const auto consider = [&](const fs::path& candidate, const std::string& why) {
    out.tried.emplace_back(candidate, why);
    if (fs::exists(candidate, ec)) out.found = candidate;
    return out.found.has_value();
  };
  if (relative.is_absolute()) {
    consider(relative, "as given");
    return out;
  }
  if (in_project && consider(relative, "the project: current directory")) return out;
  for (const auto& root : roots.roots) {
    if (consider(root.dir / relative, root.why)) return out;
  }
  if (roots.roots.empty()) out.notes.push_back(roots.none_note());
  return out;
}

ShareLookup find_shared(const fs::path& relative) {
  return find_shared(relative, true, installed_share_roots());
}

std::string ShareLookup::not_found_message(const fs::path& name) const {
  std::string text = name.string() + " not found";
  for (std::size_t i = 0; i < tried.size(); ++i) {
    text +=
        (i == 0 ? "; looked in: " : ", ") + tried[i].first.string() + " (" + tried[i].second + ")";
  }
  for (const auto& note : notes) text += "; " + note;
  return text;
}

fs::path require_shared(const fs::path& relative) {
  const ShareLookup lookup = find_shared(relative);
  if (!lookup.found) throw ConfigError(lookup.not_found_message(relative));
  return *lookup.found;
}

fs::path require_installed(const fs::path& relative) {
  const ShareLookup lookup = find_shared(relative, false, installed_share_roots());
  if (!lookup.found) throw ConfigError(lookup.not_found_message(relative));
  return *lookup.found;
}

}  // namespace cnclab
