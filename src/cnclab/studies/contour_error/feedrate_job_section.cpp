#include "cnclab/studies/contour_error/feedrate_job_section.hpp"

#include <cstdio>
#include <utility>
#include <vector>

#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {

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

void feedrate_job_metric(RunRecord& rec, const std::string& name, double value,
                         const std::string& unit) {
  rec.metrics[name] = value;
  rec.metric_units[name] = unit;
}

void feedrate_job_add_metrics(RunRecord& rec, const std::string& label,
                              const FeedrateJobMethod& m) {
  const std::string p = label + "_" + m.method + "_";
  feedrate_job_metric(rec, p + "time", m.check.time, "s");
  feedrate_job_metric(rec, p + "max", m.check.max * 1e3, "µm");
  feedrate_job_metric(rec, p + "share_within", m.check.share_within, "1");
  feedrate_job_metric(rec, p + "met", m.met ? 1.0 : 0.0, "1");
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
  opt.margin_bands = {};
  const ContourErrorModel machine = [&](const ReferenceTrajectory& r) {
    return check_on_machine(path, r, ver).simulated;
  };
  const FeedrateOptimisationResult res = optimise_feedrate(path, machine, opt, progress);
  return optimised_method("oracle", res, path, ver,
                          std::string(to_string(res.status)) + ": " + res.reason);
}

void feedrate_job_write_history(H5File& ticks, const std::string& group,
                                const FeedrateOptimisationResult& res) {
  ticks.create_group(group);
  std::vector<double> worst, time, over, cap;
  for (const auto& h : res.history) {
    worst.push_back(h.worst_predicted);
    time.push_back(h.time);
    over.push_back(static_cast<double>(h.ticks_over));
    cap.push_back(h.min_cap);
  }
  ticks.write_vector(group + "/worst_predicted", worst, "mm");
  ticks.write_vector(group + "/time", time, "s");
  ticks.write_vector(group + "/ticks_over", over);
  ticks.write_vector(group + "/min_cap", cap, "mm/s");
}

}  // namespace

std::string run_feedrate_section(const FeedrateSectionRun& run, RunRecord& rec, H5File& ticks,
                                 std::ostream& report) {
  const FeedrateJob& job = run.job;
  const PlanarPath& path = run.path;
  FeedrateOptimisationOptions opt = run.optimisation;
  VerificationOptions ver = run.verification;
  const FeedrateProfile free = plan_feedrate(path, opt.planner);
  FeedrateJobMethod unconstrained{"unconstrained", interpolate(path, free, 1e-3), {}, {}, true, ""};
  unconstrained.predicted = predict_contour_error(run.predictor, path, unconstrained.reference);
  std::string detail;
  for (const double tol_um : job.tolerances) {
    const std::string label = feedrate_tolerance_label(tol_um);
    const std::string metric = run.prefix + label, group = run.group + label;
    opt.tolerance = ver.tolerance = tol_um * 1e-3;
    ticks.create_group(group);
    if (opt.tolerance < run.contour_rms) {
      const std::string why = "tolerance " + shortest_double(tol_um) +
                              " um is below the predictor's own contour RMS error " +
                              fixed_decimals(run.contour_rms * 1e3, 2) + " um";
      rec.facts[metric + "_status"] = "below_resolution: " + why;
      ticks.set_attribute(group, "status", "below_resolution: " + why);
      report << "  " << metric << ": not planned (" << why << ")\n";
      continue;
    }
    // A line per plan and per method (each takes seconds): a log that is not
    // a terminal shows the job is alive.
    const auto say = [&](const std::string& what) {
      if (run.say) run.say(metric + ": " + what);
    };
    const auto plans_of = [&](const std::string& method) -> ProgressCallback {
      return [&say, method](const std::string&, std::size_t plans, std::size_t) {
        say(method + ", plan " + std::to_string(plans) + " done");
      };
    };
    const FeedrateOptimisationResult res =
        optimise_feedrate(path, run.predictor, opt, plans_of("constrained"));
    const FeedrateJobMethod constrained =
        optimised_method("constrained", res, path, ver, res.reason);
    say("unconstrained and uniform slowdown on the simulated machine ...");
    unconstrained.check = check_on_machine(path, unconstrained.reference, ver);
    unconstrained.met = unconstrained.check.met;
    const BaselineResult uni = uniform_slowdown(path, free, ver);
    const FeedrateJobMethod uniform{
        "uniform", uni.reference, uni.check,
        {},        uni.met,       uni.reason + "; factor " + shortest_double(uni.parameter)};
    std::vector<const FeedrateJobMethod*> methods = {&unconstrained, &constrained, &uniform};
    FeedrateJobMethod constant;
    if (job.constant_feed) {
      say("best constant feed ...");
      const BaselineResult cst = constant_feed(path, opt.planner.limits, ver);
      constant = {"constant", cst.reference,
                  cst.check,  {},
                  cst.met,    cst.reason + "; feed " + shortest_double(cst.parameter) + " mm/s"};
      methods.push_back(&constant);
    }
    FeedrateJobMethod oracle;
    if (job.oracle) {
      oracle = feedrate_job_oracle(path, opt, ver, plans_of("oracle"));
      methods.push_back(&oracle);
      feedrate_job_metric(rec, metric + "_ratio_uniform_oracle", uni.check.time / oracle.check.time,
                          "1");
      report << "  " << metric << ": oracle " << fixed_decimals(oracle.check.time, 3) << " s (max "
             << fixed_decimals(oracle.check.max * 1e3, 2) << " um, within "
             << fixed_decimals(100 * oracle.check.share_within, 2) << " %); uniform/oracle "
             << fixed_decimals(uni.check.time / oracle.check.time, 2) << "; " << oracle.note
             << "\n";
    }
    for (const FeedrateJobMethod* m : methods) {
      feedrate_job_write_method(ticks, group + "/" + m->method, *m);
      feedrate_job_add_metrics(rec, metric, *m);
    }
    feedrate_job_write_history(ticks, group + "/history", res);
    const std::string status = std::string(to_string(res.status)) + ": " + res.reason;
    ticks.set_attribute(group, "status", status);
    rec.facts[metric + "_status"] = status;
    feedrate_job_metric(rec, metric + "_plans", static_cast<double>(res.history.size()), "1");
    if (opt.uniform_candidate) {
      feedrate_job_metric(rec, metric + "_uniform_candidate_factor", res.uniform_factor, "1");
      feedrate_job_metric(rec, metric + "_uniform_candidate_chosen", res.uniform_chosen ? 1 : 0,
                          "1");
    }
    const double ratio = uni.check.time / constrained.check.time;
    feedrate_job_metric(rec, metric + "_ratio_uniform_constrained", ratio, "1");
    char line[320];
    std::snprintf(line, sizeof line,
                  "  %s: constrained %.3f s (max %.2f um, within %.2f %%, %zu plans, %s), "
                  "uniform %.3f s, constant %.3f s, unconstrained %.3f s (max %.2f um); "
                  "uniform/constrained %.2f\n",
                  metric.c_str(), constrained.check.time, constrained.check.max * 1e3,
                  100 * constrained.check.share_within, res.history.size(), to_string(res.status),
                  uni.check.time, job.constant_feed ? constant.check.time : NAN,
                  unconstrained.check.time, unconstrained.check.max * 1e3, ratio);
    report << line;
    detail +=
        (detail.empty() ? "" : "; ") + metric + " uniform/constrained " + fixed_decimals(ratio, 2);
  }
  return detail;
}

}  // namespace cnclab
