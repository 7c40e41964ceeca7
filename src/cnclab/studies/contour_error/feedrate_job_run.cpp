// Running the contour-error feedrate job (feedrate_job.hpp): the margins
// (calibrated or given), the sections of the path, each section's
// optimisation and baselines per tolerance (feedrate_job_section.hpp), the
// per-tick file and the standard result.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/studies/contour_error/feedrate_job.hpp"
#include "cnclab/studies/contour_error/feedrate_job_section.hpp"
#include "cnclab/studies/contour_error/narx_contour_model.hpp"
#include "cnclab/studies/contour_error/stored_margins.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

void feedrate_run_metric(RunRecord& rec, const std::string& name, double value,
                         const std::string& unit) {
  rec.metrics[name] = value;
  rec.metric_units[name] = unit;
}

// The residual figures of one predictor on the held-out plans, under
// `prefix` (µm but the tick count and the correlation).
void feedrate_run_residuals(RunRecord& rec, const std::string& prefix, const ResidualSummary& r) {
  feedrate_run_metric(rec, prefix + "ticks", static_cast<double>(r.ticks), "1");
  feedrate_run_metric(rec, prefix + "rms", r.rms * 1e3, "µm");
  feedrate_run_metric(rec, prefix + "underprediction_p99", r.underprediction_p99 * 1e3, "µm");
  feedrate_run_metric(rec, prefix + "underprediction_max", r.underprediction_max * 1e3, "µm");
  feedrate_run_metric(rec, prefix + "correlation", r.correlation, "1");
}

// A predictor's calibration on the plans: margins per band and residuals
// (all held-out ticks, those of the slowed runs) under `prefix`.
void feedrate_run_calibration(RunRecord& rec, const std::string& prefix,
                              const MarginCalibration& c) {
  for (std::size_t b = 0; b < c.margins.margin.size(); ++b) {
    const std::string band = prefix + "margin_band" + std::to_string(b);
    feedrate_run_metric(rec, band, c.margins.margin[b] * 1e3, "µm");
    feedrate_run_metric(rec, band + "_ticks", static_cast<double>(c.band_ticks[b]), "1");
  }
  for (std::size_t b = 0; b < c.margins.after_reversal.size(); ++b) {
    const std::string band = prefix + "margin_after_reversal_band" + std::to_string(b);
    feedrate_run_metric(rec, band, c.margins.after_reversal[b] * 1e3, "µm");
    feedrate_run_metric(rec, band + "_ticks", static_cast<double>(c.after_reversal_band_ticks[b]),
                        "1");
  }
  feedrate_run_residuals(rec, prefix + "validation_", c.validation);
  feedrate_run_residuals(rec, prefix + "slowed_", c.slowed);
}

// The start of every section [mm of arc length] (feedrate_job.hpp,
// PathSectionsOptions); the one `section` without `sections`.
std::vector<double> feedrate_section_starts(const FeedrateJob& job, const PlanarPath& path,
                                            const PlanarPath& dataset_path,
                                            const Dataset& dataset) {
  if (job.sections.count == 0) return {job.section.start};
  double from = 0.0, to = arc_length(path);
  if (job.sections.span == SectionSpan::validation) {
    const Eigen::Index u_row = dataset.metadata_row("u");
    const auto first = static_cast<Eigen::Index>(first_validation_sample(dataset));
    double u_end = dataset_path.u_begin();
    for (Eigen::Index k = first; k < dataset.metadata.cols(); ++k) {
      u_end = std::max(u_end, dataset.metadata(u_row, k));
    }
    from = arc_length(dataset_path, dataset_path.u_begin(), dataset.metadata(u_row, first), 4096);
    to = arc_length(dataset_path, dataset_path.u_begin(), u_end, 4096);
  }
  const double room = to - from - job.sections.length;
  if (room < 0) {
    throw ConfigError(job.source_file.string() + ": sections.length " +
                      shortest_double(job.sections.length) + " mm exceeds the span (" +
                      shortest_double(to - from) + " mm)");
  }
  std::vector<double> starts;
  const std::size_t n = job.sections.count;
  for (std::size_t k = 0; k < n; ++k) {
    starts.push_back(from +
                     (n == 1 ? 0.0 : room * static_cast<double>(k) / static_cast<double>(n - 1)));
  }
  return starts;
}

}  // namespace

JobReport run_feedrate_job(const FeedrateJob& job, const JobContext& c) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path& results = c.options.results_dir;
  const ResultKey key{job.name, std::nullopt, to_yaml(job), job.source_file, true};
  RunRecord rec = make_job_record("feedrate_optimisation", key, job.request);
  Dataset dataset;
  TrainedContourModel model = load_trained_contour_model(
      job.predictor_file, results, c.options.datasets_dir, c.options.profile, c.log, &dataset);
  rec.upstream.push_back({job.predictor_file.string(), model.upstream.result_file.string(),
                          result_identity(model.upstream.record)});
  ContourPredictor predictor = model.predictor();
  std::ostringstream report;
  FeedrateOptimisationOptions opt = job.optimisation;
  opt.planner = model.dataset.planner;  // the predictor's training limits and grid
  opt.prediction_margin = job.prediction_margin * 1e-3;
  VerificationOptions ver = job.verification;
  ver.machine = model.dataset.machine;  // the machine the predictor was trained on

  // The margins from the held-out plans of the predictor's dataset (with
  // calibrate_margin: those stored with the predictor's result,
  // stored_margins.hpp, calibrated and stored first if it has none), and
  // the compared predictors on the same plans.
  if (job.calibrate_margin || !job.compare_files.empty()) {
    MarginCalibration cal;
    if (job.calibrate_margin) {
      const StoredMargins stored = predictor_margins(
          predictor, dataset, model.upstream.record.dataset_hash, model.upstream.result_file,
          result_identity(model.upstream.record), job.calibration, report);
      cal = stored.calibration;
      opt.margin_bands = cal.margins;
      rec.facts["margins_file"] = stored_margins_path(model.upstream.result_file).string();
    } else {
      cal = calibrate_margins(predictor, dataset, job.calibration);
    }
    feedrate_run_calibration(rec, "calibration_", cal);
    rec.facts["calibration_inputs"] = join(model.upstream.record.narx->networks.at(0).inputs, ", ");
    report << "margins per feed band (quantile " << shortest_double(job.calibration.quantile)
           << " of simulated - predicted on " << cal.validation.ticks << " held-out ticks):";
    for (std::size_t b = 0; b < cal.margins.margin.size(); ++b) {
      report << " " << fixed_decimals(cal.margins.margin[b] * 1e3, 2) << " um";
    }
    if (!cal.margins.after_reversal.empty()) {
      report << "; within " << shortest_double(cal.margins.reversal_window * 1e3)
             << " ms of a change of direction:";
      for (const double m : cal.margins.after_reversal) {
        report << " " << fixed_decimals(m * 1e3, 2) << " um";
      }
    }
    report << "; slowed runs: p99 under-prediction "
           << fixed_decimals(cal.slowed.underprediction_p99 * 1e3, 2) << " um\n";
    for (std::size_t i = 0; i < job.compare_files.size(); ++i) {
      TrainedContourModel other = load_trained_contour_model(
          job.compare_files[i], results, c.options.datasets_dir, c.options.profile, c.log);
      rec.upstream.push_back({job.compare_files[i].string(), other.upstream.result_file.string(),
                              result_identity(other.upstream.record)});
      ContourPredictor compared = other.predictor();
      const std::string prefix = "compare" + std::to_string(i) + "_";
      feedrate_run_calibration(rec, prefix, calibrate_margins(compared, dataset, job.calibration));
      rec.facts[prefix + "name"] = other.upstream.experiment.spec.name;
      rec.facts[prefix + "inputs"] = join(other.upstream.record.narx->networks.at(0).inputs, ", ");
    }
  }

  // The path: the dataset's, or another draw of its options.
  std::unique_ptr<NurbsPlanarPath> other_path;
  if (job.path.seed) {
    Rng rng(*job.path.seed);
    other_path = std::make_unique<NurbsPlanarPath>(random_planar_nurbs(model.dataset.path, rng));
  }
  const PlanarPath& whole = other_path ? *other_path : *model.path;
  const std::vector<double> starts = feedrate_section_starts(job, whole, *model.path, dataset);
  const double length = job.sections.count == 0 ? job.section.length : job.sections.length;
  const double total = arc_length(whole);

  // Beside the result and named after it, so results of other configs keep theirs.
  const fs::path result = result_path(key, results);
  const std::string ticks_name = result.stem().string() + "-ticks.h5";
  AtomicOutput ticks_out(result.parent_path() / ticks_name);
  H5File ticks = H5File::create(ticks_out.temp_path());
  std::string detail;
  for (std::size_t k = 0; k < starts.size(); ++k) {
    if (starts[k] + length > total) {
      throw ConfigError(job.source_file.string() +
                        ": section start + length = " + shortest_double(starts[k] + length) +
                        " mm exceeds the path's " + shortest_double(total) + " mm");
    }
    const PathPiece path(whole, parameter_at_arc_length(whole, starts[k]),
                         parameter_at_arc_length(whole, starts[k] + length));
    const std::string prefix = feedrate_section_prefix(job, k);
    const std::string group = prefix.empty() ? "" : prefix.substr(0, prefix.size() - 1) + "/";
    if (!group.empty()) ticks.create_group(group.substr(0, group.size() - 1));
    if (!prefix.empty()) feedrate_run_metric(rec, prefix + "start", starts[k], "mm");
    report << "feedrate optimisation on " << shortest_double(length) << " mm of the "
           << (job.path.seed ? "path of seed " + std::to_string(*job.path.seed)
                             : std::string("dataset's path"))
           << " from " << fixed_decimals(starts[k], 1) << " mm; predictor "
           << model.upstream.result_file.string() << " (contour RMS "
           << fixed_decimals(model.contour_rms * 1e3, 2) << " um)\n";
    const FeedrateSectionRun run{job,
                                 path,
                                 predictor,
                                 opt,
                                 ver,
                                 model.contour_rms,
                                 prefix,
                                 group,
                                 [&](const std::string& what) {
                                   if (c.log) *c.log << job.name << ": " << what << std::endl;
                                 }};
    const std::string d = run_feedrate_section(run, rec, ticks, report);
    detail += (detail.empty() || d.empty() ? "" : "; ") + d;
  }
  ticks.close();
  ticks_out.commit();
  rec.outputs = {{"ticks", ticks_name}};
  rec.facts["predictor"] = model.upstream.result_file.string();
  finish_provenance(rec.provenance);
  rec.provenance.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  feedrate_run_metric(rec, "wall_seconds", rec.provenance.wall_seconds, "s");
  write_job_result(result, rec);  // last: it names the ticks file
  if (detail.size() > 400) detail = detail.substr(0, 400) + " ...";
  return JobReport{job.name, "ran",           "feedrate job (minutes; always re-run)",
                   detail,   result.string(), "== " + job.name + " ==\n" + report.str()};
}

}  // namespace cnclab
