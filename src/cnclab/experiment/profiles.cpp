#include "cnclab/experiment/profiles.hpp"

#include <algorithm>
#include <optional>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/suggest.hpp"
#include "cnclab/experiment/job_kinds.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

void add_names(std::vector<std::string>& to, const std::vector<std::string>& names) {
  for (const auto& n : names) {
    if (std::find(to.begin(), to.end(), n) == to.end()) to.push_back(n);
  }
}

std::string list_names(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ", ") + n;
  return s;
}

// "unknown profile 'quik' (did you mean 'quick'?); profiles defined by X: quick"
[[noreturn]] void unknown_profile(const std::string& profile, const std::vector<std::string>& names,
                                  const std::string& where) {
  throw ConfigError("unknown profile '" + profile + "'" + did_you_mean(profile, names) + "; " +
                    (names.empty() ? where + " define(s) no profiles"
                                   : "profiles defined by " + where + ": " + list_names(names)) +
                    " (--profile names a `profiles:` entry; without it the files run as written)");
}

struct Declared {
  std::vector<std::string> names, exclusive;
};

// The names `file` defines and those it declares exclusive (declared_profiles).
Declared declared(const fs::path& file) {
  const ConfigDocument doc = ConfigDocument::load(file);
  Declared d{doc.profiles(), doc.exclusive_profiles()};
  if (const auto kind = find_job_kind(experiment_kind(file)); kind && kind->profile_sources) {
    for (const auto& source : kind->profile_sources(file)) {
      const Declared more = declared(source);
      add_names(d.names, more.names);
      add_names(d.exclusive, more.exclusive);
    }
  }
  return d;
}

bool has(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

}  // namespace

std::vector<std::string> declared_profiles(const fs::path& file) {
  return declared(file).names;
}

void check_profile(const fs::path& file, const std::string& profile) {
  if (profile.empty()) return;
  const std::vector<std::string> names = declared_profiles(file);
  if (std::find(names.begin(), names.end(), profile) == names.end()) {
    unknown_profile(profile, names, file.string() + " and its includes");
  }
}

ProfileSet check_profile_set(const std::vector<fs::path>& files, const std::string& profile,
                             const std::string& what) {
  ProfileSet set;
  if (profile.empty()) return set;
  std::vector<std::string> names;
  std::optional<ConfigError> broken;  // the first file that does not load
  for (const auto& file : files) {
    Declared own;
    try {
      own = declared(file);
    } catch (const ConfigError& e) {
      if (!broken) broken = e;
      continue;  // the file reports its own error when it is loaded
    }
    if (!has(own.names, profile)) set.without.push_back(file);
    set.exclusive = set.exclusive || has(own.exclusive, profile);
    add_names(names, own.names);
  }
  if (!has(names, profile)) {
    // A file that does not load may be the one defining it: its error first.
    if (broken) throw *broken;
    unknown_profile(profile, names, what);
  }
  return set;
}

std::vector<fs::path> check_profile_in_set(const std::vector<fs::path>& files,
                                           const std::string& profile, const std::string& what) {
  return check_profile_set(files, profile, what).without;
}

std::string excluded_profile_note(const std::vector<fs::path>& files, const std::string& profile) {
  if (files.empty()) return "";
  constexpr std::size_t kNamed = 5;
  std::string list;
  for (std::size_t i = 0; i < files.size() && i < kNamed; ++i) {
    list += (list.empty() ? "" : ", ") + files[i].string();
  }
  if (files.size() > kNamed) list += " and " + std::to_string(files.size() - kNamed) + " more";
  return "profile " + profile + " (exclusive): not run: the " + std::to_string(files.size()) +
         " file(s) that do not define it (" + list + ")";
}

std::string undeclared_profile_note(const std::vector<fs::path>& files, const std::string& profile,
                                    const std::string& verb) {
  if (files.empty()) return "";
  std::string list;
  for (const auto& f : files) list += (list.empty() ? "" : ", ") + f.string();
  return "profile " + profile + ": not defined by " + list + ", which " + verb +
         " with their own settings";
}

}  // namespace cnclab
