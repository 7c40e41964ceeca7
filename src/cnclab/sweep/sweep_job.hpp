#pragma once
// A sweep as a job of `cnclab reproduce` (`kind: sweep`): the sweep machinery
// of `cnclab sweep` (sweep_plan.hpp, trial_pool.hpp, sweep_summary.hpp) run
// over one experiment file, into results/<name>/sweep-<plan hash>/, with the
// trial that is best by the objective as the job's selection (seed 004's
// "heuristic search": pick the network by validation MSE, report its test
// MSE).
//
// YAML (experiments/ik_search/search_x.yaml):
//   kind: sweep
//   name: ik_search_x                # results/<name>/
//   description: ...
//   experiment: ../ik/ik_x.yaml      # relative to this file
//   overrides: [trainer.epochs=500]  # plain key=value settings of every trial
//   jobs: 2                          # trials at once; 0 (default) = available cores
//   sweep: {method, trials, seed, repeats, objective: {metric, mode}, parameters: {...}}
//                                    # the `sweep:` block grammar (sweep_spec.hpp)
//   profiles: {quick: {sweep.trials: 3}}   # optional (core/config.hpp); the trials
//                                    # load the experiment with the same profile
//
// Reuse: the folder is named by the plan's hash, and a trial's identity is
// its resolved config, so running the job again runs only trials without a
// result; a finished sweep with the same plan runs nothing (`reused`).
//
// Result: the selection is a standard result file (experiment/job_result.hpp,
// kind sweep) at the result store's path for sweep_job_key (the resolved job
// and the plan hash): the selected trial's metrics plus sweep.trials,
// sweep.complete, sweep.failed, sweep.points; facts objective,
// selected_trial, selected_point; outputs selected_trial, summary, selection
// (selection.yaml, for people and scripts); upstream the selected trial.
// Status failed when no trial completed.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_spec.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {

struct SweepJob {
  std::string name;
  std::string description;
  std::filesystem::path source_file;
  JobRequest request;                  // the command's overrides and --profile (provenance only)
  std::filesystem::path experiment;    // resolved, must exist
  std::string experiment_as_written;   // as in the file (the identity holds this)
  std::vector<std::string> overrides;  // plain key=value settings of every trial
  std::size_t jobs = 0;                // 0 = the cores this process may use
  SweepSpec sweep;
  std::string profile;  // the profiles: entry applied to this file and the trials
};

// Reads a `kind: sweep` file strictly (unknown keys are ConfigErrors naming
// file:line:col), applying the profile, then `key=value` overrides of the job
// file.
SweepJob load_sweep_job(const std::filesystem::path& file,
                        const std::vector<std::string>& overrides = {},
                        const std::string& profile = {});

// The resolved job as YAML (what `cnclab validate` prints).
std::string to_yaml(const SweepJob& job);

// The selection result's identity: name, to_yaml(job) plus the plan's hash
// (which covers every trial's resolved config under the job's profile).
ResultKey sweep_job_key(const SweepJob& job, const SweepPlan& plan);

// The datasets of the job's trials that are not in the cache yet
// (options.datasets_dir), one prework each (job_kinds.hpp).
std::vector<JobPrework> sweep_job_prework(const SweepJob& job, const CommandOptions& options);

// The job's sweep as it stands in `results_dir` (nothing run or written).
struct SweepJobState {
  SweepPlan plan;
  std::filesystem::path dir;  // results/<name>/sweep-<first 8 digits of the plan hash>
  std::vector<TrialOutcome> outcomes;
  SweepSummary summary;
  // The selected trial: the best complete one by the objective; nullopt
  // while none is complete.
  std::optional<std::size_t> selected;
  bool finished() const { return summary.missing == 0; }
  // dir / trials/<id>.h5 of the selected trial; throws Error when none.
  std::filesystem::path selected_result() const;
};
SweepJobState sweep_job_state(const SweepJob& job, const std::filesystem::path& results_dir);

struct SweepJobOutcome {
  SweepJobState state;                // after the run
  std::size_t ran = 0;                // trials run now (0: reused)
  int stopped = 0;                    // signal that interrupted the trials; 0: none
  std::filesystem::path result_file;  // the selection result (empty when stopped)
  double wall_seconds = 0;
};

// Runs the trials without a result (all with options.force), writes
// summary.h5, results/<name>/selection.yaml (the selected trial: id,
// parameters, metrics, result file) and the selection result (see above),
// each atomically, when a trial ran or one of them is missing. Progress lines
// to `log` (nullptr: silent).
SweepJobOutcome run_sweep_job(const SweepJob& job, const CommandOptions& options,
                              std::ostream* log);

// One line for people: "selected <id> (key=value ...): <objective> v; k of N
// trials complete", or why nothing is selected.
std::string selection_line(const SweepJobState& state);

// `kind: sweep` for the job-kind registry (job_kinds.hpp).
JobKind sweep_job_kind();

}  // namespace cnclab
