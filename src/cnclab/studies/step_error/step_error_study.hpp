#pragma once
// The step-error study's results as `cnclab tables step-error` reads them:
// every experiment the manifest (configs/studies/step_error_tables.yaml)
// names, found through the result store (experiment/result_store.hpp), and
// the paper's numbers (results/reference/seed000_step_error.yaml).
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/report/tables.hpp"
#include "cnclab/studies/step_error/step_error_manifest.hpp"
#include "cnclab/studies/step_error/step_error_reference.hpp"
#include "cnclab/studies/step_error/step_error_repeats.hpp"
#include "cnclab/studies/step_error/step_error_stats.hpp"

namespace cnclab {

// One result of the study with the figures the tables quote.
struct StepErrorRun {
  std::string name;            // experiment name
  std::filesystem::path file;  // the result file read
  RunRecord record;
  ErrorFigures figures;
  std::string failure;  // non-empty: training failed (no figures)
};

// The run of a result read from `file`: figures when complete, `failure`
// otherwise. Error when a complete result is not one step-error target in µm.
StepErrorRun step_error_run(RunRecord record, const std::filesystem::path& file);

// Table 2's test MSE (z-score units) of a run evaluated by `inference`
// (experiment/result_inference.hpp); NaN when the result lacks that
// evaluation (written before it was stored) or the run failed.
double inference_test_mse(const StepErrorRun& run, DropoutInference inference);
// Its validation MSE (z-score units: validation.normalised_mse) so evaluated;
// NaN as above or without a validation split.
double inference_validation_mse(const StepErrorRun& run, DropoutInference inference);

struct StepErrorStudy {
  std::string profile;  // the tables' --profile ("" none)
  StudyManifest manifest;
  Seed000Reference ref;
  std::filesystem::path reference_file;
  std::map<std::filesystem::path, StepErrorRun> runs;  // experiment file -> its result
  std::optional<StepErrorRepeats> repeats;             // when the manifest has `repeats:`
  const StepErrorRun& at(const std::filesystem::path& file) const { return runs.at(file); }
  const StepErrorRun* find(const std::map<double, std::filesystem::path>& files, double key) const {
    const auto it = files.find(key);
    return it == files.end() ? nullptr : &runs.at(it->second);
  }
};

// The experiment and job files the step-error tables read (the manifest's,
// its seed sweeps and Table 8's timing job): TableEntry::experiment_files.
std::vector<std::filesystem::path> step_error_experiment_files(const TablesOptions& options);

// Every result the manifest names (the seed sweeps of `repeats:` too), read
// before anything is printed. Throws
// MissingResults (naming the command that makes it) for a missing result,
// Error for a failed one outside Table 2 (which shows divergence as such).
StepErrorStudy load_step_error_study(const TablesOptions& options);

}  // namespace cnclab
