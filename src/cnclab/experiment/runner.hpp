#pragma once
// The experiment pipeline: dataset -> split -> normalise -> model -> train ->
// evaluate -> metrics -> result file (written atomically).
#include <filesystem>
#include <functional>
#include <map>
#include <ostream>
#include <string>

#include "cnclab/core/progress.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/result_store.hpp"  // result_path: where a run writes
#include "cnclab/experiment/run_record.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {

struct RunOptions {
  std::filesystem::path results_dir = "results";
  std::filesystem::path datasets_dir = "datasets";
  ProgressMode progress = ProgressMode::automatic;
  std::ostream* log = nullptr;  // progress and notes; nullptr = silent
  // Generate the dataset even when the cache holds it (`--regenerate`).
  bool regenerate_dataset = false;
  // Where to write the result; empty = result_path(experiment, results_dir).
  // Upstream results (needs, init_from) are always looked up in results_dir.
  std::filesystem::path result_file;
  // Intermediate reports (a sweep's pruner, sweep/model_search.hpp): every
  // `report_every` epochs the trainer's current network is evaluated on the
  // validation split and `report(epoch, metric)` is called with metric
  // `report_metric` ("validation.rmse", in physical units as stored; NaN
  // when the split is empty); returning false stops training, and the
  // result is written with status "pruned" (history and metrics kept).
  std::function<bool(std::size_t epoch, double value)> report;
  std::string report_metric;
  std::size_t report_every = 1;
};

struct RunOutcome {
  std::filesystem::path result_file;
  bool ok = false;      // false: training diverged (result written with status "failed")
  std::string message;  // termination message
  std::map<std::string, double> metrics;
  std::vector<std::string> warnings;  // a complete result that is not a useful one
  std::vector<std::string> notes;     // how the run used its validation part (validation_notes)
};

// Runs one experiment. Bad configuration or I/O problems throw; a run whose
// training diverges is a failed result (written, ok = false), not an error.
RunOutcome run_experiment(const LoadedExperiment& experiment, const RunOptions& options);

// A new run's record: name, resolved config and its hash, provenance with
// the master seed and the dataset generator's derived seed.
RunRecord start_run_record(const LoadedExperiment& experiment);

// The run's dataset with generator seed `seed`, generated (with progress on
// options.log) or read from the cache (data/dataset_cache.hpp).
CachedDataset obtain_run_dataset(const ExperimentSpec& spec, std::uint64_t seed,
                                 const RunOptions& options);

}  // namespace cnclab
