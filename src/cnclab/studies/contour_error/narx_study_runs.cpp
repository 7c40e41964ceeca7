#include "cnclab/studies/contour_error/narx_study_runs.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/sweep/sweep_job.hpp"
#include "cnclab/sweep/sweep_plan.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// two_stage: open_loop stages, then closed_loop stages; open_loop_only,
// closed_loop_only; "_windowed" when a closed_loop stage has a horizon
// (the last one being the whole series or not), "_retry" when one has a
// fallback_horizon. Else the modes joined by '+'.
std::string method_of(const NarxNetworkRecord& network) {
  std::size_t open = 0, closed = 0;
  bool windowed = false, retry = false, open_after_closed = false;
  for (const auto& st : network.stages) {
    if (st.fallback) continue;  // second tries are not part of the method
    if (st.mode == "open_loop") {
      ++open;
      open_after_closed = open_after_closed || closed > 0;
    } else {
      ++closed;
      windowed = windowed || st.horizon != 0;
      retry = retry || st.fallback_horizon != 0;
    }
  }
  const std::string suffix =
      std::string(windowed ? "_windowed" : "") + std::string(retry ? "_retry" : "");
  if (!open_after_closed && open == 1 && closed > 0) return "two_stage" + suffix;
  if (open == 1 && closed == 0) return "open_loop_only";
  if (open == 0 && closed > 0) return "closed_loop_only" + suffix;
  std::string joined;
  for (const auto& st : network.stages) {
    if (!st.fallback) joined += (joined.empty() ? "" : "+") + st.mode;
  }
  return joined;
}

NarxStudyRun run_of(const RunRecord& r, const fs::path& file) {
  if (!r.narx || r.narx->networks.empty()) {
    throw IoError(file.string() + ": not a narx result (model.type narx)");
  }
  NarxStudyRun run;
  const NarxRecord& n = *r.narx;
  run.method = method_of(n.networks.front());
  run.hidden = n.options.hidden;
  run.input_delays = n.options.input_delays;
  run.feedback_delays = n.options.feedback_delays;
  run.seed = r.provenance.master_seed;
  for (const auto& st : n.networks.front().stages) {
    if (st.fallback) continue;
    (st.mode == "open_loop" ? run.open_epochs : run.closed_epochs) += st.summary.history.size();
  }
  for (const auto& net : n.networks) {
    const bool retried = std::any_of(net.stages.begin(), net.stages.end(),
                                     [](const NarxStageRecord& st) { return st.fallback; });
    run.second_tries += retried ? 1 : 0;
    if (!net.stages.empty()) {
      run.stops += (run.stops.empty() ? "" : ", ") + net.axis + ": " +
                   to_string(net.stages.back().summary.termination);
    }
  }
  // The registered names (narx_metrics.hpp): every metric of a narx run is
  // of its validation half (validation.<name>, experiment/spec.hpp).
  for (const auto& [name, value] : r.metrics) {
    if (metric_split(name) == "validation") run.metrics[metric_base(name)] = value;
  }
  return run;
}

}  // namespace

bool NarxStudyRun::bounded() const {
  const auto it = metrics.find("stable");
  return it != metrics.end() && it->second == 1.0;
}

bool NarxStudyRuns::stable(const NarxStudyRun& run) const {
  if (!run.bounded()) return false;
  for (const auto& axis : axes) {
    const std::string name = "closed_loop_rms_" + axis;
    double best = INFINITY;
    for (const auto& other : runs) {
      if (other.bounded()) best = std::min(best, other.metrics.at(name));
    }
    if (!(run.metrics.at(name) <= kStableFactor * best)) return false;
  }
  return true;
}

double NarxStudyRuns::metric(const std::string& name) const {
  const auto it = runs.front().metrics.find(name);
  return it == runs.front().metrics.end() ? std::nan("") : it->second;
}

NarxStudyRuns load_narx_study(const TablesOptions& o, const std::string& file) {
  const fs::path experiment = o.experiment_file(fs::path("contour_error") / file);
  if (!fs::exists(experiment)) throw MissingResults(experiment.string() + ": not found");
  const SweepJob job = load_sweep_job(experiment, {}, o.profile);
  const SweepJobState state = sweep_job_state(job, o.results_dir);
  NarxStudyRuns out;
  out.profile = o.profile;
  out.trials = state.plan.trials.size();
  if (state.summary.missing > 0) {
    const ResultStore store(o.results_dir, o.profile);
    throw MissingResults(std::to_string(state.summary.missing) + " of " +
                         std::to_string(out.trials) + " trials of " + experiment.string() +
                         " have no result under " + state.dir.string() + "; run `" +
                         store.make_command(sweep_job_key(job, state.plan)) + "` first");
  }
  for (std::size_t i = 0; i < state.outcomes.size(); ++i) {
    const TrialOutcome& t = state.outcomes[i];
    if (t.status != TrialOutcome::Status::complete) {
      const PlannedTrial& planned = state.plan.trials[i];
      out.not_completed.push_back(
          "trial " + planned.id + " (" + point_text(state.plan.keys, planned.values) + ", seed " +
          std::to_string(planned.seed) + "): " +
          (t.status == TrialOutcome::Status::failed ? "failed" : "error") + ": " + t.reason);
      continue;
    }
    const fs::path path = state.dir / t.result_file;
    const RunRecord r = read_result(path);
    if (out.runs.empty()) {
      for (const auto& net : r.narx->networks) out.axes.push_back(net.axis);
      out.train_samples = r.split.train.size();
      out.validation_samples = r.split.validation.size();
    }
    if (state.summary.best_trial == static_cast<std::ptrdiff_t>(i)) out.chosen = out.runs.size();
    out.runs.push_back(run_of(r, path));
    out.sources.push_back(path);
    out.configs.push_back(r.resolved_yaml);
  }
  out.objective = state.plan.objective.metric;
  if (out.runs.empty()) {
    throw MissingResults("no trial of " + experiment.string() + " completed under " +
                         state.dir.string() + " (see the .error notes there)");
  }
  return out;
}

}  // namespace cnclab
