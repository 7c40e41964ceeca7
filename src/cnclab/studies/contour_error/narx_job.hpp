#pragma once
// The NARX study job (`kind: narx`, seed 002 Sec. II-III): trains SISO NARX
// networks per axis on a `following_error` dataset (data/following_error.hpp)
// for every (architecture, training method, seed) of a grid, predicts the
// whole validation half in closed loop, and reports per run the following
// error prediction error (RMS, max, in µm), whether the closed loop stayed
// stable, and the contour error predicted by the Taylor estimate (Eqs. 3-6)
// from the predicted following errors against the exact contour error of the
// simulated data. It also reports the contour estimates' discrepancy from
// the exact value (Taylor, tangent line, osculating circle) on the data.
//
// YAML (experiments/contour_error/*.yaml), read strictly:
//   kind: narx
//   name: ...                  description: ...
//   seed: 2002                 # master seed; dataset seed default derived ("generator")
//   dataset: {generator: following_error, seed, options: {...}}
//   axes: [x, y]               # networks trained (contour accuracy needs both)
//   narx: {input_delays: 4, feedback_delays: 4, hidden: 12, activation: tanh,
//          first_input_delay: 0}
//   training:
//     open_loop:   {epochs, goal, mu, mu_dec, mu_inc, mu_max, min_gradient}   # trainbr
//     closed_loop: {...}
//   study:
//     methods: [two_stage, open_loop_only, closed_loop_only]
//     seeds: [1, 2, 3, 4, 5]   # weight-initialisation seeds (>= 1 entry)
//     architectures: [{hidden: 12, delays: 4}, ...]   # optional; delays = input = feedback
//     stable_bound: 10         # closed loop unstable: non-finite or |e_hat| > bound (normalised)
//     workers: 2               # runs trained in parallel (not part of the result identity)
// The result (HDF5, written atomically) goes to
// <results>/<name>/<name>-<16 hex of the resolved config>.h5 and is reused
// while the resolved config (defaults included) is unchanged.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/data/dataset.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/nn/narx.hpp"
#include "cnclab/train/narx_training.hpp"

namespace cnclab {

enum class NarxMethod { two_stage, open_loop_only, closed_loop_only };
std::string to_string(NarxMethod m);

struct NarxArchitecture {
  std::size_t hidden = 12;
  std::size_t input_delays = 4, feedback_delays = 4;  // YAML {hidden, delays} sets both
};

struct NarxStudyOptions {
  std::vector<NarxMethod> methods = {NarxMethod::two_stage};
  std::vector<std::uint64_t> seeds = {1};
  // Empty: the `narx` section's architecture only.
  std::vector<NarxArchitecture> architectures;
  double stable_bound = 10.0;
  std::size_t workers = 2;

  void validate() const;  // OptionError naming the field
};

struct NarxJob {
  std::string name, description;
  std::uint64_t seed = 42;
  DatasetSpec dataset;
  std::vector<std::string> axes = {"x", "y"};
  NarxOptions narx;
  NarxTrainingOptions training;  // run_open_loop/run_closed_loop set per method
  NarxStudyOptions study;
  std::filesystem::path source_file;
  std::string resolved_yaml;  // defaults included; its hash names the result
  std::string config_hash;
};

// Reads a `kind: narx` file strictly, with the named profile (top-level
// `profiles: {NAME: {dotted.key: value}}`, core/config.hpp) and then
// `key=value` overrides applied first. ConfigError naming file:line, key, value and rule.
NarxJob load_narx_job(const std::filesystem::path& file,
                      const std::vector<std::string>& overrides = {},
                      const std::string& profile = "");

// One trained network pair (architecture, method, seed) and its scores.
struct NarxAxisScore {
  double rms_um = 0, max_um = 0;  // closed-loop prediction error over the validation half
  bool stable = false;
  std::size_t open_epochs = 0, closed_epochs = 0;
  double seconds = 0;
  std::string termination;  // last stage's
};
struct NarxRun {
  NarxArchitecture architecture;
  NarxMethod method = NarxMethod::two_stage;
  std::uint64_t seed = 0;
  std::vector<NarxAxisScore> axes;  // job.axes order
  // Predicted (Taylor from predicted following errors) vs exact contour
  // error over the validation half [µm]; NaN without both axes or when unstable.
  double contour_rms_um = 0, contour_max_um = 0;
};

struct ContourEstimateRow {
  std::string method;              // taylor, tangent_line, osculating_circle
  double mean_um = 0, max_um = 0;  // |estimate - exact|
};

struct NarxStudyResult {
  std::string name, config_hash, resolved_yaml, dataset_file, dataset_hash;
  std::vector<std::string> axes;
  std::size_t train_samples = 0, validation_samples = 0;
  std::vector<NarxRun> runs;
  std::vector<double> zero_rms_um, zero_max_um;                // predicting e = 0, per axis
  double exact_contour_mean_um = 0, exact_contour_max_um = 0;  // validation half
  std::vector<ContourEstimateRow> estimates;                   // validation half
  double dataset_seconds = 0, train_seconds = 0;
  // Validation series of the first run (for figures): time [s], measured and
  // predicted following error per axis [µm], exact and predicted contour [µm].
  Eigen::MatrixXd series;
  std::vector<std::string> series_names;
};

// A following_error dataset fit for the study: right generator, every value
// finite (cnclab::Error naming `origin`, the column and the sample of a NaN),
// >= 64 samples.
void check_narx_dataset(const Dataset& dataset, const std::string& origin);

std::filesystem::path narx_result_path(const NarxJob& job, const std::filesystem::path& results);

// Runs the study (dataset from the cache under `datasets`), writes nothing.
NarxStudyResult run_narx_study(const NarxJob& job, const std::filesystem::path& datasets,
                               std::ostream* log);

void write_narx_result(const std::filesystem::path& path, const NarxStudyResult& result);
// IoError naming the file when unreadable or incomplete.
NarxStudyResult read_narx_result(const std::filesystem::path& path);

struct NarxJobOutcome {
  std::filesystem::path file;
  bool reused = false;
  NarxStudyResult result;
};
// Reuses the result of the same resolved config unless `force`; otherwise
// runs the study and writes the result atomically.
NarxJobOutcome run_narx_job(const NarxJob& job, const std::filesystem::path& results,
                            const std::filesystem::path& datasets, bool force, std::ostream* log);

// One line for a report row: best two-stage RMS, stable counts, contour RMS.
std::string narx_summary_line(const NarxStudyResult& result);

}  // namespace cnclab
