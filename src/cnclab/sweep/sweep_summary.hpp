#pragma once
// What a sweep produced: each trial's outcome read from the sweep folder, the
// points (parameter combinations) aggregated over repeats and ranked by the
// objective, and the summary HDF5 file (the table for people: sweep_report.hpp).
//
// summary.h5 (h5py: f["trials/metrics/validation.rmse"][:]):
//   /                  attrs format = "cnclab-sweep-summary", format_version = 2,
//                      experiment, method, repeats, objective_metric,
//                      objective_mode (min|max), plan_hash, counts trials,
//                      complete_trials, failed, errors, missing, pruned; best_trial (id, when
//                      any trial completed) and best_trial_rule (text); complete = 1
//                      (written last)
//   /plan              the sweep plan (sweep.yaml text)
//   /trials/{id, status, reason, result_file, seed}   strings, one per trial (plan order)
//   /trials/warnings           strings, a complete trial's warnings ("; "-separated, "" none;
//                              absent in summaries written before warnings existed)
//   /trials/{point, repeat}                           int64
//   /trials/parameters/<key>   float64 when every value is a number, else strings (YAML)
//   /trials/metrics/<metric>   float64, NaN where the trial has no metrics; attribute
//                              units when the trials' results give one
//   /points/...                one row per point, ranked by the objective (best first):
//                              point, trials (its trial ids "id1,id2,..." in
//                              repeat order), parameters/<key>, complete, failed,
//                              metrics/<metric>/{mean, std} (std over repeats, n - 1; NaN if n < 2)
//   /selected          (when a trial completed) the chosen point: attrs point,
//                      trial (= best_trial), objective_metric, complete (its
//                      repeats); /selected/metrics, /selected/metrics_std and
//                      /selected/units: one attribute per test metric
//                      (test.*), its mean and std over those repeats and unit:
//                      the test numbers of the point the objective chose,
//                      reported after the choice (none without a test split:
//                      attr note says so)
//   /importance, /pareto   model-based sweeps (search_findings.hpp)
// Metric names as in result files (validation.rmse, nn/metrics.hpp); version 1
// summaries (rmse, normalised_validation_mse, ...) are read under today's names.
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/sweep/search_findings.hpp"
#include "cnclab/sweep/sweep_plan.hpp"

namespace cnclab {

struct TrialOutcome {
  // complete / failed: a result file with that status, or (failed) a trial
  // killed by the trial timeout (its note starts with "timeout:"); error: no
  // result but a note why (exception, crash); missing: not run yet (or
  // unreadable).
  // pruned: stopped early by a model-based sweep's pruner (model_search.hpp);
  // its result keeps the history, it is done but never ranked.
  enum class Status { complete, failed, error, missing, pruned };
  Status status = Status::missing;
  std::string reason;                               // failed/error: why; missing: unreadable result
  std::map<std::string, double> metrics;            // complete only
  std::map<std::string, std::string> metric_units;  // per metric, when the result gives one
  std::vector<std::string> warnings;  // complete only ("constant predictions", run_warnings.hpp)
  std::string result_file;            // relative to the sweep folder; "" if none
  std::vector<UpstreamRef> upstream;  // upstream results the trial was made from

  // Complete or failed: resume skips it (failed ones run again with
  // --retry-failed).
  bool done() const {
    return status == Status::complete || status == Status::failed || status == Status::pruned;
  }
};
std::string to_string(TrialOutcome::Status status);

// Reads the trial's result status (read_result_status) or error note from `dir`.
TrialOutcome read_trial_outcome(const std::filesystem::path& dir, const PlannedTrial& trial);
// The same for every trial of the plan (plan order), the results read with
// one isolated child for all readable ones (read_result_statuses).
std::vector<TrialOutcome> read_trial_outcomes(const std::filesystem::path& dir,
                                              const SweepPlan& plan);

struct PointStats {
  std::size_t point = 0;
  std::vector<std::string> values;                    // per swept key
  std::vector<std::size_t> trials;                    // indices into plan.trials
  std::size_t complete = 0, failed = 0, missing = 0;  // failed includes errors
  std::size_t pruned = 0;
  std::map<std::string, double> mean, std;  // over complete repeats
};

struct SweepSummary {
  std::vector<PointStats> points;  // best first; points without results last
  std::size_t complete = 0, failed = 0, errors = 0, missing = 0;
  std::size_t pruned = 0;  // not ranked: only complete trials are
  // The best point is the first of `points` (best objective mean over its
  // complete repeats); the best trial is its median repeat by the objective
  // (of n ranked best first, the one at (n - 1) / 2), never a lucky repeat of a
  // worse point. Index into plan.trials; -1: no trial complete.
  std::ptrdiff_t best_trial = -1;
};

// metrics[name], NaN when absent.
double metric_or_nan(const std::map<std::string, double>& metrics, const std::string& name);

// The unit of each metric as the trials' results give it (the first that
// names one).
std::map<std::string, std::string> metric_units(const std::vector<TrialOutcome>& outcomes);
// The plan's metrics of the test split (test.*), in plan order: what a sweep
// reports of its chosen point, after the choice.
std::vector<std::string> test_metrics(const SweepPlan& plan);

// How best_trial is chosen (summary.h5 attribute best_trial_rule).
inline constexpr const char* kBestTrialRule = "median repeat of the rank-1 point by the objective";
// What a sweep without test metrics reports of its chosen point (narx runs:
// split.mode sequential_halves has no test part).
inline constexpr const char* kNoTestSplitNote =
    "no test split: no part is held out of both the training and the choice, so the chosen "
    "point's numbers are no estimate on new data";

SweepSummary summarize(const SweepPlan& plan, const std::vector<TrialOutcome>& outcomes);

// Written atomically (layout above); `search`: a model-based sweep's
// importance and Pareto front (search_findings.hpp).
void write_summary(const std::filesystem::path& file, const SweepPlan& plan,
                   const std::vector<TrialOutcome>& outcomes, const SweepSummary& summary,
                   const SearchFindings* search = nullptr);

// What a summary.h5 records, read back without touching the sweep folder:
// the plan and each trial's outcome as the summary saw it (status, reason,
// result file, warnings, and for complete trials the plan's metrics;
// upstream is not stored). summarize(plan, outcomes) gives its ranking again.
struct StoredSummary {
  SweepPlan plan;
  std::vector<TrialOutcome> outcomes;
  std::string best_trial;                // the recorded best trial's id ("" if none)
  std::optional<SearchFindings> search;  // a model-based sweep's
};
inline constexpr const char* kSummaryFormat = "cnclab-sweep-summary";
// IoError naming the file when it is not a complete summary or its trials do
// not match its plan.
StoredSummary read_summary(const std::filesystem::path& file);
// True for an HDF5 file whose root `format` is kSummaryFormat (IoError when
// it is not a readable HDF5 file).
bool is_sweep_summary(const std::filesystem::path& file);

}  // namespace cnclab
