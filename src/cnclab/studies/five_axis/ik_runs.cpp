#include "cnclab/studies/five_axis/ik_runs.hpp"

#include <algorithm>

#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/sweep/sweep_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

std::string lower(const std::string& axis) {
  return std::string(1, static_cast<char>(axis[0] - 'A' + 'a'));
}

// Checks that `result` is a run for the single target `axis` (the store
// returned it complete).
IkAxisRun checked(const std::string& axis, const fs::path& source, LoadedExperiment loaded,
                  StoredResult result) {
  IkAxisRun run{
      axis, source, std::move(loaded), std::move(result.file), {}, std::move(result.record)};
  if (run.record.target_names != std::vector<std::string>{axis}) {
    throw Error(run.result_file.string() + ": expected the single target " + axis);
  }
  return run;
}

// An ordinary experiment's result: experiments/<folder>/ik_<axis>.yaml.
IkAxisRun load_experiment_axis(const TablesOptions& o, const std::string& folder,
                               const std::string& axis) {
  const fs::path file = o.experiment_file(fs::path(folder) / ("ik_" + lower(axis) + ".yaml"));
  if (!fs::exists(file)) throw MissingResults(file.string() + ": experiment file not found");
  const ResultStore store = table_store(o);
  LoadedExperiment loaded = store.load(file);
  StoredResult result = store.get(loaded);
  return checked(axis, file, std::move(loaded), std::move(result));
}

// The trial the search job selected: its selection result (sweep_job.hpp,
// found by the job's resolved config and plan) names it.
IkAxisRun load_search_axis(const TablesOptions& o, const std::string& axis, std::string& note) {
  const fs::path file =
      o.experiment_file(fs::path("ik_search") / ("search_" + lower(axis) + ".yaml"));
  if (!fs::exists(file)) throw MissingResults(file.string() + ": sweep job file not found");
  const SweepJob job = load_sweep_job(file, {}, o.profile);
  const SweepPlan plan =
      plan_sweep(job.experiment, job.overrides, std::nullopt, job.sweep, job.profile);
  const StoredResult selection = table_store(o).get(sweep_job_key(job, plan));
  const RunRecord& s = selection.record;
  const auto count = [&](const std::string& name) {
    const auto it = s.metrics.find(name);
    if (it == s.metrics.end()) throw IoError(selection.file.string() + ": no metric " + name);
    return std::to_string(static_cast<long long>(it->second));
  };
  const auto fact = [&](const std::string& name) {
    const auto it = s.facts.find(name);
    if (it == s.facts.end()) throw IoError(selection.file.string() + ": no fact " + name);
    return it->second;
  };
  const std::string id = fact("selected_trial");
  const auto trial = std::find_if(plan.trials.begin(), plan.trials.end(),
                                  [&](const PlannedTrial& t) { return t.id == id; });
  if (trial == plan.trials.end()) {
    throw IoError(selection.file.string() + ": selected trial " + id + " is not in the plan");
  }
  const std::string objective = fact("objective");
  note = axis + ": the best point by mean " + objective.substr(0, objective.find(' ')) + " of " +
         count("sweep.points") + " (" + count("sweep.complete") + " complete trial(s) of " +
         count("sweep.trials") + " planned), its median repeat";
  const fs::path result = output_path(s, selection.file, "selected_trial");
  IkAxisRun run = checked(axis, result, *trial->experiment, {result, read_result(result)});
  run.selection = selection.file;
  return run;
}

}  // namespace

bool IkVariant::any() const {
  for (const auto& a : axes) {
    if (a) return true;
  }
  return false;
}

std::vector<fs::path> ik_experiment_files(const TablesOptions& o) {
  std::vector<fs::path> files;
  for (const char* axis : kIkAxes) {
    for (const std::string& name :
         {"ik/ik_" + lower(axis) + ".yaml", "ik_search/search_" + lower(axis) + ".yaml",
          "ik_trainbr/ik_" + lower(axis) + ".yaml"}) {
      try {
        const fs::path file = o.experiment_file(name);
        if (fs::exists(file)) files.push_back(file);
      } catch (const MissingResults&) {
        // a variant without this axis (the search has no A and C)
      }
    }
  }
  return files;
}

std::vector<IkVariant> load_ik_variants(const TablesOptions& o) {
  std::vector<IkVariant> out(3);
  out[0].key = "sgdm", out[0].label = "ours";
  out[1].key = "search", out[1].label = "search";
  out[2].key = "trainbr", out[2].label = "trainbr";
  for (std::size_t i = 0; i < kIkAxes.size(); ++i) {
    const std::string axis = kIkAxes[i];
    out[0].axes[i] = load_experiment_axis(o, "ik", axis);
    try {
      std::string note;
      out[1].axes[i] = load_search_axis(o, axis, note);
      out[1].notes.push_back(note);
    } catch (const MissingResults& e) {
      out[1].notes.push_back(axis + " not available: " + e.what());
    }
    try {
      out[2].axes[i] = load_experiment_axis(o, "ik_trainbr", axis);
    } catch (const MissingResults& e) {
      out[2].notes.push_back(axis + " not available: " + e.what());
    }
  }
  // A variant with no axis at all: one note (the first axis's reason).
  for (auto& v : out) {
    if (!v.any() && !v.notes.empty()) {
      v.notes = {"no results for any axis; " + v.notes.front()};
    }
  }
  return out;
}

}  // namespace cnclab
