#pragma once
// Seed 000 Table 8: time to obtain the step errors of the surface-2 and
// surface-3 test sets of the 15 % fine-tuning experiments, in one run, by
//   (a) the iterative geometric method the paper compares against
//       (geometry/step_error.hpp iterative_step_error: discrete points on the
//       CC curve, zoom on the extreme; seed 000 refs. 1-3, 26),
//   (b) our exact method (grid bracket + safeguarded Newton),
//   (c) the network: read the model from the experiment's result file,
//       compute its 73 inputs (K points on the local CC curve, CC and CL
//       points, R) from the tool path, normalise, forward pass.
// All three start from the same planned tool-path lines (CC curve, CC and CL
// points of every line holding a test segment), timed once and reported
// separately: the geometric methods need the CC curve and CL points as much
// as the network needs its inputs, and the paper's network read precomputed
// samples, so its 2.861 / 2.798 s exclude both planning and the inputs (our
// "forward only" figure is the comparable one; "network total" is the honest
// end-to-end figure from the same start as the geometric methods).
// Each method runs `repeats` times; the median is reported. Single thread.
// Consistency checks (errors if violated): the exact method reproduces the
// dataset's targets of the test samples and the network the result file's
// test predictions, so the timed work is the work the tables report.
//
// YAML (experiments/step_error/table8_timing.yaml):
//   kind: step_error_timing
//   name: step_error_table8_timing
//   description: ...
//   experiments: {surface2: FILE, surface3: FILE}   # relative to this file
//   repeats: 3
//   iterative: {points_per_pass: 10, relative_tolerance: 1e-6, max_passes: 100}
//   profiles: {quick: {repeats: 1}}
// Output: a standard result file (experiment/job_result.hpp, kind
// step_error_timing) at the result store's path for the resolved job
// (results/<name>/<name>-<hash>.h5, atomic): metrics "<surface>.<field>"
// (seconds, µm, counts), the timed results as its upstream; read by `cnclab
// tables step-error`, `cnclab show` and `cnclab compare`.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cnclab/core/fields.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/geometry/step_error.hpp"

namespace cnclab {

struct StepErrorTimingOptions {
  std::size_t repeats = 3;  // timings per method; the median is reported. >= 1
  IterativeStepErrorOptions iterative;
  void validate() const;
};

// A timing file's keys below kind, name, description and experiments:
// repeats and iterative.
const FieldList<StepErrorTimingOptions>& step_error_timing_fields();
// Every key of a timing file, for its schema: kind, name, description,
// experiments, then the options above.
std::vector<FieldInfo> step_error_timing_file_fields();

struct StepErrorTimingJob {
  std::string name;  // file-name-safe; results/<name>/
  std::string description;
  // Table 8's surfaces ("surface2", "surface3") -> resolved experiment file,
  // and as written in the file (relative to it; what the identity holds, so
  // it does not depend on how the job file was named on the command line).
  std::map<std::string, std::filesystem::path> experiments;
  std::map<std::string, std::string> experiments_as_written;
  StepErrorTimingOptions options;
  std::filesystem::path source_file;
  JobRequest request;   // the command's overrides and --profile (provenance only)
  std::string profile;  // applied to the upstream experiments as well
};

// Reads a `kind: step_error_timing` file strictly (unknown keys are errors),
// applying the `profiles:` entry `profile` (core/config.hpp; the upstream
// experiments load with it too), then `key=value` overrides.
StepErrorTimingJob load_step_error_timing_job(const std::filesystem::path& file,
                                              const std::vector<std::string>& overrides = {},
                                              const std::string& profile = {});

// The resolved job as YAML that loads back to the same job (`cnclab validate`;
// the result's identity).
std::string to_yaml(const StepErrorTimingJob& job);

// Timings of one surface's test set [s] (medians over the repeats).
struct SurfaceTiming {
  std::string surface;
  std::string experiment;       // experiment name
  std::string experiment_file;  // its file
  std::string result_file;      // the model that was loaded
  std::string identity;         // result_identity of that result (upstream.hpp)
  std::size_t test_samples = 0;
  std::size_t lines = 0;         // tool-path lines planned
  double planning_s = 0;         // the tool path: CC curves, CC/CL points, checks (shared start)
  double iterative_s = 0;        // (a)
  double exact_s = 0;            // (b)
  double network_load_s = 0;     // (c) read the result file, build the network
  double network_inputs_s = 0;   // (c) 73 inputs per sample from the planned lines
  double network_forward_s = 0;  // (c) normalise, forward pass, back to µm
  double network_total_s() const { return network_load_s + network_inputs_s + network_forward_s; }
  // Accuracy of each method against the exact value [µm].
  double iterative_max_error_um = 0;
  double network_max_error_um = 0;
};

struct StepErrorTimingResult {
  std::string name;
  std::string host, utc, cnclab_version, git_commit;
  std::size_t repeats = 0;
  double wall_seconds = 0;  // the whole timing [s]
  std::vector<SurfaceTiming> surfaces;
};

// Times every surface; reads the upstream results from results_dir (the
// result store with the job's profile). Throws MissingResults when an
// experiment has no result there.
StepErrorTimingResult run_step_error_timing(const StepErrorTimingJob& job,
                                            const std::filesystem::path& results_dir);

// The result's identity: the job's name and resolved YAML (it has upstream results).
ResultKey step_error_timing_key(const StepErrorTimingJob& job);
// Writes the result (job_result.hpp) atomically at store.path_of(key); returns the file.
std::filesystem::path write_step_error_timing(const StepErrorTimingJob& job,
                                              const StepErrorTimingResult& result,
                                              const ResultStore& store);
// One line per run for `cnclab reproduce`: each surface's seconds by method.
std::string step_error_timing_summary(const StepErrorTimingResult& result);
// The timing of a result record; IoError naming `file` when it is not a
// step_error_timing result or lacks a surface's figures.
StepErrorTimingResult read_step_error_timing(const RunRecord& record,
                                             const std::filesystem::path& file);

}  // namespace cnclab
