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

}  // namespace

std::vector<std::string> declared_profiles(const fs::path& file) {
  std::vector<std::string> names = ConfigDocument::load(file).profiles();
  if (const auto kind = find_job_kind(experiment_kind(file)); kind && kind->profile_sources) {
    for (const auto& source : kind->profile_sources(file)) {
      add_names(names, declared_profiles(source));
    }
  }
  return names;
}

void check_profile(const fs::path& file, const std::string& profile) {
  if (profile.empty()) return;
  const std::vector<std::string> names = declared_profiles(file);
  if (std::find(names.begin(), names.end(), profile) == names.end()) {
    unknown_profile(profile, names, file.string() + " and its includes");
  }
}

std::vector<fs::path> check_profile_in_set(const std::vector<fs::path>& files,
                                           const std::string& profile, const std::string& what) {
  std::vector<fs::path> without;
  if (profile.empty()) return without;
  std::vector<std::string> names;
  std::optional<ConfigError> broken;  // the first file that does not load
  for (const auto& file : files) {
    std::vector<std::string> own;
    try {
      own = declared_profiles(file);
    } catch (const ConfigError& e) {
      if (!broken) broken = e;
      continue;  // the file reports its own error when it is loaded
    }
    if (std::find(own.begin(), own.end(), profile) == own.end()) without.push_back(file);
    add_names(names, own);
  }
  if (std::find(names.begin(), names.end(), profile) == names.end()) {
    // A file that does not load may be the one defining it: its error first.
    if (broken) throw *broken;
    unknown_profile(profile, names, what);
  }
  return without;
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
