#include "cnclab/pipeline/reproduce_inputs.hpp"

#include <algorithm>
#include <optional>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/profiles.hpp"

namespace cnclab {
namespace fs = std::filesystem;

std::vector<fs::path> find_experiments(const std::vector<std::string>& paths) {
  std::vector<fs::path> files;
  const std::vector<std::string> roots =
      paths.empty() ? std::vector<std::string>{"experiments"} : paths;
  for (const auto& root : roots) {
    std::error_code ec;
    if (fs::is_regular_file(root, ec)) {
      files.emplace_back(root);
    } else if (fs::is_directory(root, ec)) {
      for (auto it = fs::recursive_directory_iterator(root); it != fs::end(it); ++it) {
        const auto& entry = *it;
        if (entry.is_directory() && fs::exists(entry.path() / kOptInMarker)) {
          it.disable_recursion_pending();  // an opt-in set: only when named
          continue;
        }
        const auto ext = entry.path().extension();
        if (entry.is_regular_file() && (ext == ".yaml" || ext == ".yml"))
          files.push_back(entry.path());
      }
    } else {
      throw ConfigError(root + ": no such experiment file or folder");
    }
  }
  std::sort(files.begin(), files.end());
  files.erase(std::unique(files.begin(), files.end()), files.end());
  return files;
}

ReproduceInputs reproduce_inputs(const std::vector<std::string>& paths,
                                 const std::string& profile) {
  auto found = find_experiments(paths);
  if (found.empty()) throw ConfigError("reproduce: no experiment files found");
  ReproduceInputs inputs;
  const ProfileSet set = check_profile_set(
      found, profile, "the " + std::to_string(found.size()) + " experiment file(s) given");
  if (set.exclusive) {  // only the files that define it (profiles.hpp)
    std::erase_if(found, [&](const fs::path& f) {
      return std::find(set.without.begin(), set.without.end(), f) != set.without.end();
    });
    inputs.profile_note = excluded_profile_note(set.without, profile);
  } else {
    inputs.profile_note = undeclared_profile_note(set.without, profile);
  }
  for (const auto& file : found) {
    std::optional<JobKind> kind;
    try {
      kind = find_job_kind(experiment_kind(file));
    } catch (const ConfigError&) {
    }
    if (kind) {
      inputs.jobs.emplace_back(file, std::move(*kind));
    } else {
      inputs.files.push_back(file);
    }
  }
  // What the jobs read, unless given: one file, one node of the graph.
  std::set<fs::path> known;
  for (const auto& file : inputs.files) known.insert(fs::weakly_canonical(file));
  for (const auto& [file, kind] : inputs.jobs) {
    if (!kind.upstream) continue;
    try {
      for (const auto& up : kind.upstream(file, profile)) {
        // Only training experiments; the job's own run names any other file.
        if (experiment_kind(up) != "train") continue;
        if (known.insert(fs::weakly_canonical(up)).second) inputs.files.push_back(up);
      }
    } catch (const std::exception&) {
      // the job's own run reports it
    }
  }
  return inputs;
}

std::vector<JobPrework> jobs_prework(const std::vector<std::pair<fs::path, JobKind>>& jobs,
                                     const CommandOptions& options) {
  std::vector<JobPrework> out;
  if (options.regenerate) return out;
  std::set<std::string> keys;
  const JobContext context{options, {}, nullptr};
  for (const auto& [file, kind] : jobs) {
    if (!kind.prework) continue;
    try {
      for (auto& p : kind.prework(file, context)) {
        if (keys.insert(p.key).second) out.push_back(std::move(p));
      }
    } catch (const std::exception&) {
    }
  }
  return out;
}

}  // namespace cnclab
