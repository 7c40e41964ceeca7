#include "cnclab/studies/contour_error/feedrate_job.hpp"

#include <yaml-cpp/yaml.h>

#include "cnclab/core/config.hpp"
#include "cnclab/core/field_schema.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

const FieldList<PathSectionOptions>& feedrate_job_section_fields() {
  using S = PathSectionOptions;
  static const auto fields =
      FieldList<S>()
          .field("start", &S::start, "arc length from the path start [mm]", Rule::non_negative())
          .field("length", &S::length, "arc length of the section [mm]", Rule::positive());
  return fields;
}

const FieldList<PathSectionsOptions>& feedrate_job_sections_fields() {
  using S = PathSectionsOptions;
  static const auto fields =
      FieldList<S>()
          .field("count", &S::count, "sections, evenly spaced over the span (0: the one `section`)")
          .field("length", &S::length, "arc length of each section [mm]", Rule::positive())
          .choice("span", &S::span,
                  {{"validation", SectionSpan::validation}, {"path", SectionSpan::path}},
                  "validation: the arc lengths of the dataset's validation half; path: the "
                  "whole path");
  return fields;
}

const FieldList<FeedratePathOptions>& feedrate_job_path_fields() {
  using P = FeedratePathOptions;
  static const auto fields = FieldList<P>().field(
      "seed", &P::seed,
      "another random path with the dataset's path options, drawn from this seed (absent: the "
      "dataset's own path)");
  return fields;
}

const FieldList<MarginCalibrationOptions>& feedrate_job_calibration_fields() {
  using C = MarginCalibrationOptions;
  static const auto fields =
      FieldList<C>()
          .field("quantile", &C::quantile,
                 "the margin of a band: this quantile of simulated - predicted contour error "
                 "on the held-out plans",
                 Rule::in(0, false, 1, false))
          .field("feed_bands", &C::feed_bands,
                 "band edges of the tick's path speed [mm/s], ascending", Rule::positive())
          .field("min_ticks", &C::min_ticks,
                 "a band with fewer held-out ticks takes the quantile of its class, or of all",
                 Rule::at_least(1))
          .field("reversal_window", &C::reversal_window,
                 "[s]: ticks this long after either axis changed direction (or started) get "
                 "margins of their own per band (0: one class)",
                 Rule::non_negative())
          .omit_default();
  return fields;
}

const FieldList<FeedrateOptimisationOptions>& feedrate_job_optimisation_fields() {
  using O = FeedrateOptimisationOptions;
  static const auto fields =
      FieldList<O>()
          .field("safety_factor", &O::safety_factor,
                 "s: caps aim at s eps_max (feedrate_optimisation.hpp)",
                 Rule::in(0, false, 1, true))
          .field("error_exponent", &O::error_exponent,
                 "p in |eps| ~ v^p: caps scale by (s eps_max / |eps|)^(1/p)", Rule::positive())
          .field("margin", &O::margin, "arc length each side of an exceeding tick [mm]",
                 Rule::non_negative())
          .field("raise_caps", &O::raise_caps,
                 "two-sided cap update: caps also rise where the prediction is below the "
                 "target; the fastest plan within tolerance - margin of all plans is kept")
          .field("uniform_candidate", &O::uniform_candidate,
                 "also the unconstrained plan slowed by the largest factor the predictor keeps "
                 "within tolerance - margin (bisection); the faster plan is kept")
          .omit_default()
          .field("uniform_steps", &O::uniform_steps, "bisection steps of the uniform candidate",
                 Rule::at_least(1))
          .omit_default()
          .field("min_factor", &O::min_factor, "slowest factor of the uniform candidate",
                 Rule::in(0, false, 1, false))
          .omit_default()
          .field("max_iterations", &O::max_iterations, "plans, the first included",
                 Rule::at_least(1))
          .field("min_speed", &O::min_speed, "a cap below this [mm/s]: infeasible",
                 Rule::positive())
          .field("standstill_speed", &O::standstill_speed,
                 "ticks of a plan slower than this [mm/s] are not held to the bound (the "
                 "jerk-limited start and stop no cap changes); at most min_speed",
                 Rule::non_negative())
          .omit_default();
  return fields;
}

const FieldList<VerificationOptions>& feedrate_job_verification_fields() {
  using V = VerificationOptions;
  static const auto fields =
      FieldList<V>()
          .field("seed", &V::seed, "the simulated machine's scale-noise seed")
          .field("required_share", &V::required_share,
                 "share of ticks within eps_max for a reference to meet it",
                 Rule::in(0, false, 1, true))
          .field("bisection_steps", &V::bisection_steps, "bisection steps of each baseline",
                 Rule::at_least(1))
          .field("min_factor", &V::min_factor,
                 "slowest slowdown factor / share of the best constant feed tried",
                 Rule::in(0, false, 1, false));
  return fields;
}

}  // namespace

const FieldList<FeedrateJob>& feedrate_job_fields() {
  using J = FeedrateJob;
  static const auto fields =
      FieldList<J>()
          .field("predictor", &J::predictor,
                 "the narx experiment whose trained predictor plans (relative to this file); "
                 "its dataset gives the path, limits and machine")
          .section("section", &J::section, feedrate_job_section_fields(),
                   "the part of the dataset's path")
          .section("sections", &J::sections, feedrate_job_sections_fields(),
                   "many sections declared up front, instead of `section`")
          .omit_default()
          .section("path", &J::path, feedrate_job_path_fields(),
                   "the path planned on (absent: the dataset's)")
          .omit_default()
          .field("tolerances", &J::tolerances, "eps_max values [µm]", Rule::positive())
          .field("prediction_margin", &J::prediction_margin,
                 "what the predictor may under-predict the machine's contour error by [µm]; "
                 "the loop plans for a predicted error within tolerance - margin",
                 Rule::non_negative())
          .field("oracle", &J::oracle,
                 "also run the loop with the simulated machine as its error model (a perfect "
                 "predictor, margin 0): method oracle, the loop's own limit (a diagnostic)")
          .field("calibrate_margin", &J::calibrate_margin,
                 "the margin per feed band stored with the predictor's result (its residuals "
                 "on its dataset's validation plans; calibrated and stored first when the "
                 "result has none for these options), instead of prediction_margin")
          .omit_default()
          .section("calibration", &J::calibration, feedrate_job_calibration_fields(),
                   "the margin calibration (margin_calibration.hpp)")
          .omit_default()
          .field("compare_predictors", &J::compare_predictors,
                 "narx experiments (relative to this file) scored on the same held-out plans")
          .omit_default()
          .field("constant_feed", &J::constant_feed, "run the best-constant-feed baseline")
          .omit_default()
          .section("optimisation", &J::optimisation, feedrate_job_optimisation_fields(),
                   "the predictive optimisation (feedrate_optimisation.hpp)")
          .section("verification", &J::verification, feedrate_job_verification_fields(),
                   "the simulated machine check and the baselines");
  return fields;
}

std::vector<FieldInfo> feedrate_file_fields() {
  std::vector<FieldInfo> fields = job_file_fields("feedrate_optimisation");
  for (auto& f : feedrate_job_fields().info()) fields.push_back(std::move(f));
  return fields;
}

FeedrateJob load_feedrate_job(const fs::path& file, const std::vector<std::string>& overrides,
                              const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  for (const auto& text : overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  if (root.get<std::string>("kind", "") != "feedrate_optimisation") {
    root.fail("kind", "must be feedrate_optimisation");
  }
  FeedrateJob job;
  job.source_file = file;
  job.request = {overrides, profile};
  job.name = read_experiment_name(root);
  job.description = root.get<std::string>("description", "");
  feedrate_job_fields().read(root, job);
  root.validate([&] { feedrate_job_fields().check(job); });
  job.predictor_file = upstream_file(root, "predictor", job.predictor, file.parent_path());
  for (const auto& text : job.compare_predictors) {
    job.compare_files.push_back(
        upstream_file(root, "compare_predictors", text, file.parent_path()));
  }
  root.check(!job.tolerances.empty(), "tolerances", "must list at least one tolerance [µm]");
  root.check(!(job.calibrate_margin && job.prediction_margin != 0.0), "prediction_margin",
             "must be 0 with calibrate_margin: true (the margin comes from the calibration)");
  root.section("calibration").validate([&] { job.calibration.validate(); });
  for (const double t : job.tolerances) {
    root.check(t > job.prediction_margin, "tolerances",
               "every tolerance must exceed prediction_margin " +
                   std::to_string(job.prediction_margin) + " µm");
  }
  root.section("optimisation").validate([&] { job.optimisation.validate(); });
  root.section("verification").validate([&] { job.verification.validate(); });
  doc.check_all_consumed();
  return job;
}

std::string feedrate_tolerance_label(double tolerance_um) {
  return "eps" + shortest_double(tolerance_um) + "um";
}

std::string feedrate_section_prefix(const FeedrateJob& job, std::size_t k) {
  if (job.sections.count == 0) return "";
  std::string digits = std::to_string(k);
  if (digits.size() < 2) digits.insert(0, 2 - digits.size(), '0');
  return "s" + digits + "_";
}

std::string to_yaml(const FeedrateJob& job) {
  using YAML::Key, YAML::Value;
  YAML::Emitter out;
  out << YAML::BeginMap << Key << "kind" << Value << "feedrate_optimisation" << Key << "name"
      << Value << job.name << Key << "description" << Value << job.description;
  feedrate_job_fields().emit(out, job);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

JobKind feedrate_job_kind() {
  JobKind kind = job_kind("feedrate_optimisation",
                          "predictive feedrate optimisation with a contour-error constraint, "
                          "verified on the simulated machine (seed 002)",
                          load_feedrate_job, run_feedrate_job);
  kind.upstream = [](const fs::path& file, const std::string& profile) {
    const FeedrateJob job = load_feedrate_job(file, {}, profile);
    std::vector<fs::path> files{job.predictor_file};
    files.insert(files.end(), job.compare_files.begin(), job.compare_files.end());
    return files;
  };
  kind.schema = [] {
    return object_schema(feedrate_file_fields(),
                         "kind feedrate_optimisation: the fastest feedrate within a contour "
                         "tolerance, by the trained NARX predictor");
  };
  return kind;
}

}  // namespace cnclab
