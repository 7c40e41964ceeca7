#pragma once
// The contour-error feedrate job (`kind: feedrate_optimisation`, docs/motion.md):
// on a section of the seed-002 dataset's random NURBS path, at the
// dataset's axis limits and on its simulated machine, for each tolerance:
// the predictive feedrate optimisation (feedrate_optimisation.hpp) with the
// trained NARX predictor of an upstream narx experiment, verified on the
// simulated machine, and the baselines (contour_verification.hpp).
//
// YAML (experiments/contour_error/feedrate.yaml):
//   kind: feedrate_optimisation
//   name: contour_error_feedrate
//   description: ...
//   predictor: narx.yaml            # the narx experiment, relative to this file
//   section: {start: 0, length: 150}     # arc length of the dataset's path [mm]
//   tolerances: [10, 5, 3]          # eps_max [µm]
//   prediction_margin: 0            # [µm], the loop plans for eps_max - margin
//   oracle: false                   # also plan with the simulated machine as the model
//   optimisation: {safety_factor, error_exponent, margin, max_iterations, min_speed, grid_spacing}
//   verification: {seed, required_share, bisection_steps, min_factor}
// and for the study over many sections (docs/motion.md, "Any path"), each
// key optional:
//   sections: {count: 15, length: 150, span: validation}   # instead of section
//   path: {seed: 7}                 # another random path of the dataset's options
//   calibrate_margin: true          # margins per feed band stored with the predictor
//   calibration: {quantile, feed_bands, min_ticks}   # margin_calibration.hpp
//   compare_predictors: [../narx.yaml]   # scored on the same held-out plans
//   constant_feed: false            # skip the best-constant-feed baseline
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/core/fields.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/studies/contour_error/contour_verification.hpp"
#include "cnclab/studies/contour_error/feedrate_optimisation.hpp"
#include "cnclab/studies/contour_error/margin_calibration.hpp"

namespace cnclab {

struct PathSectionOptions {
  double start = 0.0;     // arc length from the path start [mm], >= 0
  double length = 150.0;  // [mm], > 0; start + length within the path
};

// Sections declared before any result is seen: `count` sections of `length`
// evenly spaced over the span, the first at its start, the last ending at
// its end. span "validation": the arc lengths the dataset's validation half
// covers on its path (the same interval on another path, path.seed);
// "path": the whole path.
enum class SectionSpan { validation, path };
struct PathSectionsOptions {
  std::size_t count = 0;  // 0: the one `section` instead
  double length = 150.0;  // [mm], > 0
  SectionSpan span = SectionSpan::validation;
};

// The path planned on: the predictor's dataset's random NURBS path, or with
// `seed` another draw of the same options (a path neither the predictor's
// training nor its margin calibration saw).
struct FeedratePathOptions {
  std::optional<std::uint64_t> seed;
};

struct FeedrateJob {
  std::string name, description;
  std::string predictor = "narx.yaml";   // as written
  std::filesystem::path predictor_file;  // resolved against the job file's folder
  PathSectionOptions section;
  PathSectionsOptions sections;
  FeedratePathOptions path;
  std::vector<double> tolerances = {10.0, 5.0, 3.0};  // [µm]
  // What the predictor may under-predict the machine by [µm]
  // (FeedrateOptimisationOptions::prediction_margin); < every tolerance.
  double prediction_margin = 0.0;
  // Also run the loop with the simulated machine as its error model (a
  // perfect predictor, margin 0): method "oracle", what the loop itself
  // reaches apart from the predictor's error (a diagnostic; the simulated
  // machine is not available to a real controller).
  bool oracle = false;
  // The loop's margin per feed band from the predictor's residuals on its
  // dataset's validation plans (margin_calibration.hpp) instead of
  // prediction_margin (which must then be 0): the calibration stored with
  // the predictor's result (stored_margins.hpp), made and stored first when
  // that result has none for these options.
  bool calibrate_margin = false;
  MarginCalibrationOptions calibration;
  // narx experiments whose predictors are scored on the same held-out plans
  // as the job's (its dataset's validation part): the comparison the
  // predictor was chosen by, and the paper's predictor before it.
  std::vector<std::string> compare_predictors;  // as written
  std::vector<std::filesystem::path> compare_files;
  bool constant_feed = true;                 // run the best-constant-feed baseline
  FeedrateOptimisationOptions optimisation;  // tolerance and limits set per run
  VerificationOptions verification;          // tolerance and machine set per run
  std::filesystem::path source_file;
  JobRequest request;  // the command's overrides and --profile (provenance only)
};

// The declared keys below kind, name and description.
const FieldList<FeedrateJob>& feedrate_job_fields();
std::vector<FieldInfo> feedrate_file_fields();  // every key, for the schema

// Strict load with profile and overrides (ConfigError naming file and key).
FeedrateJob load_feedrate_job(const std::filesystem::path& file,
                              const std::vector<std::string>& overrides = {},
                              const std::string& profile = {});
std::string to_yaml(const FeedrateJob& job);

// "eps<um>um": a tolerance's group in the per-tick file and the prefix of its
// metrics and facts in the result (what `cnclab tables feedrate` reads).
std::string feedrate_tolerance_label(double tolerance_um);
// "s<k>_" (two digits at least): the prefix of section k's metrics and
// facts, and "s<k>/" its group in the per-tick file, when the job has
// sections; "" for the one section.
std::string feedrate_section_prefix(const FeedrateJob& job, std::size_t k);

// Runs the job and writes <results>/<name>/<name>-ticks.h5 (per tolerance and
// method: time, u, feed, predicted and simulated contour error per tick; the
// history) and the standard result naming it (metrics per tolerance and
// method), or reuses a current result (same config, same predictor).
JobReport run_feedrate_job(const FeedrateJob& job, const JobContext& context);

// The registered kind.
JobKind feedrate_job_kind();

}  // namespace cnclab
