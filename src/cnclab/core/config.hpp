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
#include <vector>

#include "cnclab/core/override.hpp"
#include "cnclab/core/source_location.hpp"

namespace cnclab {

class ConfigReader;

class ConfigDocument {
 public:
  // Loads `file` and resolves `include:` (a path or list of paths, relative to
  // the including file; "configs/..." also resolves against the nearest
  // ancestor directory holding configs/). Included documents are merged in
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
  // unchanged; "" selects none. ConfigError when `profiles` is not a map of
  // maps or an entry is not a valid `key: value` override.
  static ConfigDocument load(const std::filesystem::path& file, const std::string& profile = {});
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

// A path named in a config file, resolved the way `include:` is: relative to
// the naming file, else "configs/..." against the nearest ancestor directory
// of that file holding configs/. A missing file is returned as the relative
// path (the reader reports it).
std::filesystem::path resolve_config_path(const std::filesystem::path& including_file,
                                          const std::string& name);

// Flow-style one-line text of a node, for messages.
std::string node_text(const YAML::Node& node);

}  // namespace cnclab

#include "cnclab/core/config_impl.hpp"
