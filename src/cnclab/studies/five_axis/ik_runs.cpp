#include "cnclab/studies/five_axis/ik_runs.hpp"

#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/sweep/sweep_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

std::string lower(const std::string& axis) {
  return std::string(1, static_cast<char>(axis[0] - 'A' + 'a'));
}

// Checks that `result` is a complete run for the single target `axis`.
IkAxisRun checked(const std::string& axis, const fs::path& source, LoadedExperiment loaded,
                  const fs::path& result) {
  IkAxisRun run{axis, source, std::move(loaded), read_result(result)};
  if (run.record.target_names != std::vector<std::string>{axis}) {
    throw Error(result.string() + ": expected the single target " + axis);
  }
  if (run.record.provenance.status != "complete") {
    throw Error(result.string() + ": training failed (" + run.record.provenance.failure_reason +
                ")");
  }
  return run;
}

// An ordinary experiment's result: experiments/<folder>/ik_<axis>.yaml.
IkAxisRun load_experiment_axis(const TablesOptions& o, const std::string& folder,
                               const std::string& axis) {
  const fs::path file = o.experiments_dir / folder / ("ik_" + lower(axis) + ".yaml");
  if (!fs::exists(file)) throw MissingResults(file.string() + ": experiment file not found");
  LoadedExperiment loaded =
      load_experiment(file, std::vector<std::string>{}, std::nullopt, o.profile);
  const fs::path result = result_path(loaded, o.results_dir);
  if (!fs::exists(result)) {
    throw MissingResults("no result for " + file.string() + " (expected " + result.string() +
                         "); run `cnclab reproduce " + (o.experiments_dir / folder).string() +
                         "` first");
  }
  return checked(axis, file, std::move(loaded), result);
}

// The trial the search job selected (its sweep finished: every trial has a
// result or an error note).
IkAxisRun load_search_axis(const TablesOptions& o, const std::string& axis, std::string& note) {
  const fs::path file = o.experiments_dir / "ik_search" / ("search_" + lower(axis) + ".yaml");
  if (!fs::exists(file)) throw MissingResults(file.string() + ": sweep job file not found");
  const SweepJob job = load_sweep_job(file, {}, o.profile);
  const SweepJobState s = sweep_job_state(job, o.results_dir);
  const std::size_t have = s.plan.trials.size() - s.summary.missing;
  if (!s.finished()) {
    throw MissingResults(file.string() + ": " + std::to_string(have) + " of " +
                         std::to_string(s.plan.trials.size()) + " trials have results in " +
                         s.dir.string() + "; run `cnclab reproduce " +
                         (o.experiments_dir / "ik_search").string() + "`");
  }
  if (!s.selected) throw Error(file.string() + ": no trial of the search completed");
  note = axis + ": the best point by mean " + s.plan.objective.metric + " of " +
         std::to_string(s.summary.points.size()) + " (" + std::to_string(s.summary.complete) +
         " complete trial(s) of " + std::to_string(s.plan.trials.size()) +
         " planned), its median repeat";
  return checked(axis, s.selected_result(), *s.plan.trials[*s.selected].experiment,
                 s.selected_result());
}

}  // namespace

bool IkVariant::any() const {
  for (const auto& a : axes) {
    if (a) return true;
  }
  return false;
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
