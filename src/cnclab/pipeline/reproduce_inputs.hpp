#pragma once
// What `cnclab reproduce` runs from the paths it is given: the experiment
// files found, split into training experiments (the graph) and `kind:` jobs,
// the training experiments the jobs read, and the jobs' prework.
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/experiment/job_kinds.hpp"

namespace cnclab {

// Experiment YAML files under `paths` (files as given, folders recursively),
// sorted; a missing path is a ConfigError. A folder below a given one that
// holds a file kOptInMarker is an opt-in set (a study too long for
// `reproduce` of everything, README command 1): skipped unless it is
// itself given (or a folder or file inside it).
inline constexpr const char* kOptInMarker = "OPT_IN.md";
std::vector<std::filesystem::path> find_experiments(const std::vector<std::string>& paths);

// What reproduce runs from `paths`: training experiments (the graph) and
// `kind: <job>` files (job_kinds.hpp, after the graph); a file whose kind
// cannot be read stays in the graph, to be reported there.
struct ReproduceInputs {
  std::vector<std::filesystem::path> files;
  std::vector<std::pair<std::filesystem::path, JobKind>> jobs;
  // The files found under `paths` that do not define the profile (they run
  // with their own settings, or, for an exclusive profile, are left out;
  // experiment/profiles.hpp): one line, or "".
  std::string profile_note;
};
// The experiment files under `paths` split into training experiments and
// `kind:` jobs; the training experiments a job reads (JobKind::upstream,
// loaded with `profile`) are added to the training files once. ConfigError
// when no file found defines `profile` (the set rule of profiles.hpp). With
// an exclusive profile, the files that do not define it are not run.
ReproduceInputs reproduce_inputs(const std::vector<std::string>& paths, const std::string& profile);

// What the jobs need that does not wait for training (their datasets), each
// piece (JobPrework::key) once, in job order. None with --regenerate (the
// jobs regenerate their own). A job whose prework cannot be listed (a bad
// file) reports that when it runs.
std::vector<JobPrework> jobs_prework(
    const std::vector<std::pair<std::filesystem::path, JobKind>>& jobs,
    const CommandOptions& options);

}  // namespace cnclab
