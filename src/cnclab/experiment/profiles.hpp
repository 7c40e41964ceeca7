#pragma once
// `--profile NAME` names one of the `profiles:` entries that the files define
// (core/config.hpp). The rule, the same for every command that takes it:
// - one file (`run`, `validate`, `sweep`): NAME is defined by the file or its
//   includes, or, for a job, by the files its profile reaches
//   (JobKind::profile_sources: a `kind: sweep` file's experiment, whose
//   trials load with the profile);
// - a set of files (`reproduce`, `tables`): NAME is defined by at least one
//   file of the set. A file of the set that does not define it runs (or is
//   read) with its own settings, and the command says which files those are;
//   unless the profile is exclusive (`profile.exclusive: true` in its entry,
//   core/config.hpp, in a file of the set, its includes or profile sources):
//   then `reproduce` runs only the files that define it and says how many it
//   left out. `quick` is a variant of every study (a file without it is
//   already quick); `converged` is a variant of seed 002's studies only.
// Anything else is a ConfigError (exit 2) naming the profile, the nearest
// defined name ("did you mean") and the names defined, so a misspelt profile
// never runs the full configuration quietly.
#include <filesystem>
#include <string>
#include <vector>

namespace cnclab {

// The profile names `file` defines: its `profiles:` and its includes', and
// for a job file those of its JobKind::profile_sources. ConfigError for a
// file that does not load.
std::vector<std::string> declared_profiles(const std::filesystem::path& file);

// ConfigError unless `profile` is "" or declared_profiles(file) has it.
void check_profile(const std::filesystem::path& file, const std::string& profile);

// The set rule: ConfigError unless `profile` is "" or at least one of
// `files` defines it (`what` names the set in the message: "the 12 files
// given", "the study's experiment files"); when none does and a file does
// not load, that file's error. Returns the files that do not define it
// (they run or are read with their own settings; a file that does not load
// is left to report its error when it is loaded).
std::vector<std::filesystem::path> check_profile_in_set(
    const std::vector<std::filesystem::path>& files, const std::string& profile,
    const std::string& what);

// check_profile_in_set's rule and its result, and whether a file of the set
// declares `profile` exclusive.
struct ProfileSet {
  std::vector<std::filesystem::path> without;  // the files that do not define it
  bool exclusive = false;
};
ProfileSet check_profile_set(const std::vector<std::filesystem::path>& files,
                             const std::string& profile, const std::string& what);

// "profile converged (exclusive): not run: the 3 file(s) that do not define
// it (a.yaml, b.yaml, c.yaml)", at most 5 names, then "and N more"; "" for none.
std::string excluded_profile_note(const std::vector<std::filesystem::path>& files,
                                  const std::string& profile);

// "profile quick: not defined by a.yaml, b.yaml, which run with their own
// settings" for check_profile_in_set's files ("" when there are none).
std::string undeclared_profile_note(const std::vector<std::filesystem::path>& files,
                                    const std::string& profile, const std::string& verb = "run");

}  // namespace cnclab
