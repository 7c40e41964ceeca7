// Running the contour-error feedrate job (feedrate_job.hpp): the section of
// the dataset's path, the optimisation and the baselines per tolerance, the
// per-tick file and the standard result.
#include <chrono>
#include <cmath>
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
#include "cnclab/studies/contour_error/narx_contour_model.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// The part of a path between two arc lengths, reparameterised on nothing:
// the same C(u) over [u0, u1].
class FeedrateJobSection final : public PlanarPath {
 public:
  FeedrateJobSection(const PlanarPath& path, double u0, double u1)
      : path_(path), u0_(u0), u1_(u1) {}
  double u_begin() const override { return u0_; }
  double u_end() const override { return u1_; }
  PathPoint evaluate(double u) const override { return path_.evaluate(u); }

 private:
  const PlanarPath& path_;
  double u0_, u1_;
};

// Parameter at arc length s from the path start, by bisection on the
// quadrature arc length (monotone in u).
double feedrate_job_parameter_at(const PlanarPath& path, double s) {
  double lo = path.u_begin(), hi = path.u_end();
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (arc_length(path, path.u_begin(), mid, 256) < s ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// One method's per-tick series and metrics of one tolerance.
struct FeedrateJobMethod {
  std::string method;
  ReferenceTrajectory reference;
  ContourCheck check;
  std::vector<double> predicted;  // empty when not predicted
  bool met = false;
  std::string note;
};

void feedrate_job_write_method(H5File& f, const std::string& group, const FeedrateJobMethod& m) {
  f.create_group(group);
  f.write_vector(group + "/time", m.reference.time, "s");
  f.write_vector(group + "/u", m.reference.u);
  std::vector<double> feed(m.reference.time.size());
  for (Eigen::Index k = 0; k < m.reference.samples(); ++k) {
    feed[static_cast<std::size_t>(k)] = m.reference.velocity.row(k).norm();
  }
  f.write_vector(group + "/feed", feed, "mm/s");
  f.write_matrix(group + "/position", m.reference.position, "mm");
  f.write_vector(group + "/simulated", m.check.simulated, "mm");
  if (!m.predicted.empty()) f.write_vector(group + "/predicted", m.predicted, "mm");
  f.set_attribute(group, "met", static_cast<std::int64_t>(m.met));
  f.set_attribute(group, "note", m.note);
}

void feedrate_job_add_metrics(RunRecord& rec, const std::string& label,
                              const FeedrateJobMethod& m) {
  const std::string p = label + "_" + m.method + "_";
  rec.metrics[p + "time"] = m.check.time;
  rec.metric_units[p + "time"] = "s";
  rec.metrics[p + "max"] = m.check.max * 1e3;
  rec.metric_units[p + "max"] = "µm";
  rec.metrics[p + "share_within"] = m.check.share_within;
  rec.metric_units[p + "share_within"] = "1";
  rec.metrics[p + "met"] = m.met ? 1.0 : 0.0;
  rec.metric_units[p + "met"] = "1";
}

// An optimised plan as a table row: its reference checked on the machine.
FeedrateJobMethod optimised_method(std::string method, const FeedrateOptimisationResult& res,
                                   const PlanarPath& path, const VerificationOptions& ver,
                                   std::string reason) {
  return {std::move(method),
          res.reference,
          check_on_machine(path, res.reference, ver),
          res.predicted,
          res.status == OptimisationStatus::converged,
          std::move(reason)};
}

// The loop with the simulated machine (the verification's, same seed) as
// its error model: a perfect predictor, so no margin.
FeedrateJobMethod feedrate_job_oracle(const PlanarPath& path, FeedrateOptimisationOptions opt,
                                      const VerificationOptions& ver,
                                      const ProgressCallback& progress) {
  opt.prediction_margin = 0.0;
  const ContourErrorModel machine = [&](const ReferenceTrajectory& r) {
    return check_on_machine(path, r, ver).simulated;
  };
  const FeedrateOptimisationResult res = optimise_feedrate(path, machine, opt, progress);
  return optimised_method("oracle", res, path, ver,
                          std::string(to_string(res.status)) + ": " + res.reason);
}

}  // namespace

JobReport run_feedrate_job(const FeedrateJob& job, const JobContext& c) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path& results = c.options.results_dir;
  const ResultKey key{job.name, std::nullopt, to_yaml(job), job.source_file, true};
  RunRecord rec = make_job_record("feedrate_optimisation", key, job.request);
  TrainedContourModel model = load_trained_contour_model(
      job.predictor_file, results, c.options.datasets_dir, c.options.profile, c.log);
  rec.upstream.push_back({job.predictor_file.string(), model.upstream.result_file.string(),
                          result_identity(model.upstream.record)});
  ContourPredictor predictor =
      contour_predictor_from(model.upstream.record, model.ranges, model.upstream.result_file);

  const double total = arc_length(*model.path);
  if (job.section.start + job.section.length > total) {
    throw ConfigError(job.source_file.string() + ": section.start + section.length = " +
                      shortest_double(job.section.start + job.section.length) +
                      " mm exceeds the dataset path's " + shortest_double(total) + " mm");
  }
  const FeedrateJobSection path(
      *model.path, feedrate_job_parameter_at(*model.path, job.section.start),
      feedrate_job_parameter_at(*model.path, job.section.start + job.section.length));
  FeedrateOptimisationOptions opt = job.optimisation;
  opt.planner = model.dataset.planner;  // the predictor's training limits and grid
  VerificationOptions ver = job.verification;
  ver.machine = model.dataset.machine;  // the machine the predictor was trained on

  const FeedrateProfile free = plan_feedrate(path, opt.planner);
  FeedrateJobMethod unconstrained{"unconstrained", interpolate(path, free, 1e-3), {}, {}, true, ""};
  unconstrained.predicted = predict_contour_error(predictor, path, unconstrained.reference);

  // Beside the result and named after it, so results of other configs keep theirs.
  const fs::path result = result_path(key, results);
  const std::string ticks_name = result.stem().string() + "-ticks.h5";
  AtomicOutput ticks_out(result.parent_path() / ticks_name);
  H5File ticks = H5File::create(ticks_out.temp_path());
  std::ostringstream report;
  report << "feedrate optimisation on " << shortest_double(job.section.length)
         << " mm of the seed-002 path from " << shortest_double(job.section.start)
         << " mm; predictor " << model.upstream.result_file.string() << " (contour RMS "
         << fixed_decimals(model.contour_rms * 1e3, 2) << " um)\n";
  std::string detail;
  for (const double tol_um : job.tolerances) {
    const std::string label = feedrate_tolerance_label(tol_um);
    opt.tolerance = ver.tolerance = tol_um * 1e-3;
    opt.prediction_margin = job.prediction_margin * 1e-3;
    ticks.create_group(label);
    if (opt.tolerance < model.contour_rms) {
      const std::string why = "tolerance " + shortest_double(tol_um) +
                              " um is below the predictor's own contour RMS error " +
                              fixed_decimals(model.contour_rms * 1e3, 2) + " um";
      rec.facts[label + "_status"] = "below_resolution: " + why;
      ticks.set_attribute(label, "status", "below_resolution: " + why);
      report << "  " << label << ": not planned (" << why << ")\n";
      continue;
    }
    // A line per plan and per method (each takes seconds): a log that is not
    // a terminal shows the job is alive.
    const auto say = [&](const std::string& what) {
      if (c.log) *c.log << job.name << ": " << label << ": " << what << std::endl;
    };
    const auto plans_of = [&](const std::string& method) -> ProgressCallback {
      return [&say, method](const std::string&, std::size_t plans, std::size_t) {
        say(method + ", plan " + std::to_string(plans) + " done");
      };
    };
    const FeedrateOptimisationResult res =
        optimise_feedrate(path, predictor, opt, plans_of("constrained"));
    const FeedrateJobMethod constrained =
        optimised_method("constrained", res, path, ver, res.reason);
    say("unconstrained and uniform slowdown on the simulated machine ...");
    unconstrained.check = check_on_machine(path, unconstrained.reference, ver);
    unconstrained.met = unconstrained.check.met;
    const BaselineResult uni = uniform_slowdown(path, free, ver);
    say("best constant feed ...");
    const BaselineResult cst = constant_feed(path, opt.planner.limits, ver);
    const FeedrateJobMethod uniform{
        "uniform", uni.reference, uni.check,
        {},        uni.met,       uni.reason + "; factor " + shortest_double(uni.parameter)};
    const FeedrateJobMethod constant{
        "constant", cst.reference,
        cst.check,  {},
        cst.met,    cst.reason + "; feed " + shortest_double(cst.parameter) + " mm/s"};
    std::vector<const FeedrateJobMethod*> methods = {&unconstrained, &constrained, &uniform,
                                                     &constant};
    FeedrateJobMethod oracle;
    if (job.oracle) {
      oracle = feedrate_job_oracle(path, opt, ver, plans_of("oracle"));
      methods.push_back(&oracle);
      rec.metrics[label + "_ratio_uniform_oracle"] = uni.check.time / oracle.check.time;
      rec.metric_units[label + "_ratio_uniform_oracle"] = "1";
      report << "  " << label << ": oracle " << fixed_decimals(oracle.check.time, 3) << " s (max "
             << fixed_decimals(oracle.check.max * 1e3, 2) << " um, within "
             << fixed_decimals(100 * oracle.check.share_within, 2) << " %); uniform/oracle "
             << fixed_decimals(uni.check.time / oracle.check.time, 2) << "; " << oracle.note
             << "\n";
    }
    for (const FeedrateJobMethod* m : methods) {
      feedrate_job_write_method(ticks, label + "/" + m->method, *m);
      feedrate_job_add_metrics(rec, label, *m);
    }
    const std::string hist = label + "/history";
    ticks.create_group(hist);
    std::vector<double> worst, time, over, cap;
    for (const auto& h : res.history) {
      worst.push_back(h.worst_predicted);
      time.push_back(h.time);
      over.push_back(static_cast<double>(h.ticks_over));
      cap.push_back(h.min_cap);
    }
    ticks.write_vector(hist + "/worst_predicted", worst, "mm");
    ticks.write_vector(hist + "/time", time, "s");
    ticks.write_vector(hist + "/ticks_over", over);
    ticks.write_vector(hist + "/min_cap", cap, "mm/s");
    ticks.set_attribute(label, "status", std::string(to_string(res.status)) + ": " + res.reason);
    rec.facts[label + "_status"] = std::string(to_string(res.status)) + ": " + res.reason;
    rec.metrics[label + "_plans"] = static_cast<double>(res.history.size());
    rec.metric_units[label + "_plans"] = "1";
    const double ratio = uni.check.time / constrained.check.time;
    rec.metrics[label + "_ratio_uniform_constrained"] = ratio;
    rec.metric_units[label + "_ratio_uniform_constrained"] = "1";
    char line[320];
    std::snprintf(line, sizeof line,
                  "  %s: constrained %.3f s (max %.2f um, within %.2f %%, %zu plans, %s), "
                  "uniform %.3f s, constant %.3f s, unconstrained %.3f s (max %.2f um); "
                  "uniform/constrained %.2f\n",
                  label.c_str(), constrained.check.time, constrained.check.max * 1e3,
                  100 * constrained.check.share_within, res.history.size(), to_string(res.status),
                  uni.check.time, cst.check.time, unconstrained.check.time,
                  unconstrained.check.max * 1e3, ratio);
    report << line;
    detail +=
        (detail.empty() ? "" : "; ") + label + " uniform/constrained " + fixed_decimals(ratio, 2);
  }
  ticks.close();
  ticks_out.commit();
  rec.outputs = {{"ticks", ticks_name}};
  rec.facts["predictor"] = model.upstream.result_file.string();
  finish_provenance(rec.provenance);
  rec.provenance.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rec.metrics["wall_seconds"] = rec.provenance.wall_seconds;
  rec.metric_units["wall_seconds"] = "s";
  write_job_result(result, rec);  // last: it names the ticks file
  return JobReport{job.name, "ran",           "feedrate job (minutes; always re-run)",
                   detail,   result.string(), "== " + job.name + " ==\n" + report.str()};
}

}  // namespace cnclab
