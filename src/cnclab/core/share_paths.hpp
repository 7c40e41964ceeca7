#pragma once
// Where cnclab's shared files are: the configs (configs/), the studies'
// experiment files (experiments/), the papers' reference numbers
// (results/reference/), the figure scripts (scripts/figures/) and the project
// template of `cnclab init` (templates/project/). Each share root is laid out
// like the repository root, so a file's name is the same in every one.
//
// A project's own files come first (the current directory, and for includes
// the configs/ folders of config_lookup), then cnclab's own share roots:
//  1. EXE/../share/cnclab, EXE the running executable (/proc/self/exe): an
//     installed cnclab (`cmake --install build --prefix P`: P/bin/cnclab and
//     P/share/cnclab; the .deb: /usr/bin and /usr/share/cnclab);
//  2. CNCLAB_SHARE_DIR, the install location compiled in
//     (CMAKE_INSTALL_PREFIX/share/cnclab), for an executable copied elsewhere;
//  3. the source tree, when the executable lies inside the build tree it was
//     built in (build/cnclab and the test binaries of a checkout).
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace cnclab {

// A folder laid out like the repository root, and why it is searched.
struct ShareRoot {
  std::filesystem::path dir;
  std::string why;  // "installed, next to the executable", ...
};

// The share roots that exist, in the order above, each once.
struct ShareRoots {
  std::vector<ShareRoot> roots;
  // The candidates that do not exist, for messages ("EXE/../share/cnclab =
  // /opt/x/share/cnclab: absent").
  std::vector<std::string> absent;
  // "no cnclab share folder (ABSENT, ...)": what a message says when `roots`
  // is empty.
  std::string none_note() const;
};

// cnclab's own share roots (1-3 above) for the running executable, worked
// out at each call.
ShareRoots installed_share_roots();
// The same for an executable at `executable` (tests): "" takes only the
// compiled-in folder.
ShareRoots share_roots_for(const std::filesystem::path& executable);

// Where a file was looked for.
struct ShareLookup {
  std::optional<std::filesystem::path> found;                        // the first existing candidate
  std::vector<std::pair<std::filesystem::path, std::string>> tried;  // in order, with why
  std::vector<std::string> notes;  // ShareRoots::none_note() when there was none
  // "NAME not found; looked in: P1 (why), P2 (why); NOTES".
  std::string not_found_message(const std::filesystem::path& name) const;
};

// `relative` ("results/reference/ik_table5.yaml") as given, relative to the
// current directory (the project), when `in_project`, then under each root.
// An absolute name is only itself.
ShareLookup find_shared(const std::filesystem::path& relative, bool in_project,
                        const ShareRoots& roots);
// The same in the project, then installed_share_roots().
ShareLookup find_shared(const std::filesystem::path& relative);

// The file find_shared(relative) finds; a ConfigError listing every place
// looked when there is none.
std::filesystem::path require_shared(const std::filesystem::path& relative);

// `relative` in cnclab's own share roots only, not the project (the project
// template of `cnclab init`); a ConfigError listing the places otherwise.
std::filesystem::path require_installed(const std::filesystem::path& relative);

}  // namespace cnclab
