#pragma once
// Experiment configuration: a YAML tree resolved from a file, its includes and
// command-line overrides, with the source location of every key, read into
// typed options through ConfigReader with strict validation.
//
// Every error names where: "experiments/x.yaml:12:14: trainer.momentum = 1.5:
// must be in [0, 1)". A key nobody reads is an error (check_all_consumed), so
// a typo never silently falls back to a default.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/core/override.hpp"
#include "cnclab/core/share_paths.hpp"
#include "cnclab/core/source_location.hpp"

namespace cnclab {

class ConfigReader;

// Where a config file named in another one (`include:`, a dataset's
// `surface:` or `machine:`) is searched besides the naming file's folder; see
// lookup_config_path. The loaders' default is from_environment(), evaluated
// at each call (nothing is cached); tests pass one explicitly.
struct ConfigSearch {
  // CNCLAB_CONFIG_PATH: configs folders, each laid out like the repository's
  // configs/ (trainers/, machines/, surfaces/, ...), searched in order.
  std::vector<std::filesystem::path> config_path;
  // The current directory: its configs/ is searched after the config path;
  // "" searches none.
  std::filesystem::path current_dir;
  // cnclab's own share roots (share_paths.hpp): ROOT/configs of each is
  // searched last (an installed cnclab's configs, or the source tree's).
  ShareRoots shared;

  // CNCLAB_CONFIG_PATH split at ':' (empty entries skipped), the current
  // directory of the process and installed_share_roots().
  static ConfigSearch from_environment();
};

class ConfigDocument {
 public:
  // Loads `file` and resolves `include:` (a path or list of paths, found by
  // lookup_config_path; a name that is found nowhere is a ConfigError listing
  // every place searched). Included documents are merged in
  // order, then the including file's own keys: later keys override earlier
  // ones (maps merge key by key; scalars and lists are replaced).
  //
  // `profiles:` (top level) holds named sets of overrides, for example
  //   profiles:
  //     quick: {trainer.epochs: 20, dataset.options.samples: 2000}
  // load() and parse() take the block out of the tree after the includes are
  // merged (an included file's profiles are inherited; the including file's
  // entries win key by key), so it is never part of the resolved
  // configuration, then apply the entries of `profile` as overrides (before
  // any command-line override). A profile the file does not define leaves it
  // unchanged here ("" selects none): whether an unknown name is an error is
  // the command's rule (a file of a set may lack a profile others define;
  // experiment/profiles.hpp), so the names defined are kept (profiles()).
  // An entry's keys under `profile.` are settings of the profile, not
  // overrides: `profile.exclusive: true` says that a set of files given
  // the profile runs only the files that define it (experiment/profiles.hpp).
  // ConfigError when `profiles` is not a map of maps, an entry is not a
  // valid `key: value` override, or a `profile.` key is unknown or not a
  // boolean.
  static ConfigDocument load(const std::filesystem::path& file, const std::string& profile = {},
                             const ConfigSearch& search = ConfigSearch::from_environment());
  // A document from YAML text (tests, fuzzing); `origin` names it in messages.
  static ConfigDocument parse(const std::string& yaml_text, const std::string& origin,
                              const std::string& profile = {});

  // Sets path = value, creating maps on the way; it is an error to descend
  // into a value that is not a map.
  void apply(const Override& override);

  ConfigReader root() const;
  // The resolved tree as YAML text (what `validate` prints and results store).
  std::string to_yaml() const;
  const std::string& origin() const { return origin_; }
  // The profile names the file and its includes define (`profiles:` keys,
  // in file order), whichever profile was applied.
  const std::vector<std::string>& profiles() const { return profiles_; }
  // Those of them whose entry says `profile.exclusive: true`.
  const std::vector<std::string>& exclusive_profiles() const { return exclusive_profiles_; }

  // Location of a dotted key, or of its nearest located ancestor.
  SourceLocation location(const std::string& dotted_key) const;
  // Throws ConfigError for the first key in the tree that no reader consumed.
  void check_all_consumed() const;

 private:
  friend class ConfigReader;
  struct State {
    std::map<std::string, SourceLocation> locations;
    std::set<std::string> consumed;
  };
  void take_profiles(const std::string& profile);

  YAML::Node tree_;
  std::string origin_;
  std::vector<std::string> profiles_;
  std::vector<std::string> exclusive_profiles_;
  std::shared_ptr<State> state_ = std::make_shared<State>();
};

// A view of one map in the document at a dotted path. Reading a key marks it
// consumed. Errors carry the file position and dotted key.
class ConfigReader {
 public:
  ConfigReader(const ConfigDocument& doc, YAML::Node node, std::string path);

  bool has(const std::string& key) const;
  // Typed reads. Supported T: double, bool, std::string, std::int64_t,
  // std::uint64_t, std::size_t (non-negative integers), and std::vector of
  // those. Numbers must be finite.
  template <class T>
  T get(const std::string& key, const T& fallback) const;
  template <class T>
  T require(const std::string& key) const;
  template <class T>
  std::optional<T> optional(const std::string& key) const;

  // A nested map (an absent key gives an empty section).
  ConfigReader section(const std::string& key) const;
  // The raw node of a key, marked consumed with everything beneath it.
  YAML::Node raw(const std::string& key) const;
  // Entry `index` of the list at `key`, a map, as a reader named
  // "<path>.<key>[<index>]" (its keys are not checked by check_all_consumed:
  // read the list with raw() and check the entry's keys yourself).
  ConfigReader element(const std::string& key, std::size_t index) const;
  std::vector<std::string> keys() const;

  std::string dotted(const std::string& key) const;
  SourceLocation location(const std::string& key) const;
  const std::string& path() const { return path_; }

  // Throws ConfigError "<location>: <path.key> = <value>: <rule>".
  [[noreturn]] void fail(const std::string& key, const std::string& rule) const;
  // Runs `validate` (an options struct's validate()); an OptionError it
  // throws is re-thrown with the location of `path().field`.
  template <class F>
  void validate(F&& validate) const;

  // Range helpers: fail(key, rule) unless the condition holds.
  void check(bool ok, const std::string& key, const std::string& rule) const {
    if (!ok) fail(key, rule);
  }

 private:
  [[noreturn]] void rethrow_option_error(const class OptionError& e) const;
  YAML::Node child(const std::string& key) const;
  void mark(const std::string& key) const;

  const ConfigDocument* doc_;
  YAML::Node node_;
  std::string path_;
};

// Where a path named in a config file is, searched in this order:
//  1. relative to the naming file's folder (an absolute name: only itself);
//  2. a name "configs/REST" names a file in a configs folder, searched then in
//     a. ANCESTOR/configs/REST for every folder from the naming file's upward
//        that has a configs/ folder (the project or repository root),
//     b. ENTRY/REST for every entry of search.config_path (CNCLAB_CONFIG_PATH),
//     c. CWD/configs/REST for search.current_dir,
//     d. ROOT/configs/REST for every root of search.shared (an installed
//        cnclab's share folder, or the source tree of a build-tree binary).
// Other relative names are searched only next to the naming file.
struct ConfigLookup {
  std::optional<std::filesystem::path> found;  // the first existing candidate
  // Every candidate, in search order, each with why it was tried ("relative
  // to the naming file", "CNCLAB_CONFIG_PATH", ...).
  std::vector<std::pair<std::filesystem::path, std::string>> tried;
  // What else the message should say ("CNCLAB_CONFIG_PATH is not set", ...).
  std::vector<std::string> notes;
  // "not found; looked in: P1 (why), P2 (why), ...; NOTES" for an error.
  std::string not_found_message() const;
};
ConfigLookup lookup_config_path(const std::filesystem::path& naming_file, const std::string& name,
                                const ConfigSearch& search);

// The file lookup_config_path finds, or, when none exists, the first
// candidate (its reader reports it missing).
std::filesystem::path resolve_config_path(
    const std::filesystem::path& naming_file, const std::string& name,
    const ConfigSearch& search = ConfigSearch::from_environment());

// Flow-style one-line text of a node, for messages.
std::string node_text(const YAML::Node& node);

}  // namespace cnclab

#include "cnclab/core/config_impl.hpp"
