#include "cnclab/studies/contour_error/narx_study_runs.hpp"

#include <cmath>

#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/sweep/sweep_job.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

std::string method_of(const NarxNetworkRecord& network) {
  std::vector<std::string> modes;
  for (const auto& st : network.stages) modes.push_back(st.mode);
  if (modes == std::vector<std::string>{"open_loop", "closed_loop"}) return "two_stage";
  if (modes == std::vector<std::string>{"open_loop"}) return "open_loop_only";
  if (modes == std::vector<std::string>{"closed_loop"}) return "closed_loop_only";
  std::string joined;
  for (const auto& m : modes) joined += (joined.empty() ? "" : "+") + m;
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
    (st.mode == "open_loop" ? run.open_epochs : run.closed_epochs) = st.summary.history.size();
  }
  run.metrics = r.metrics;
  return run;
}

}  // namespace

bool NarxStudyRun::stable() const {
  const auto it = metrics.find("stable");
  return it != metrics.end() && it->second == 1.0;
}

double NarxStudyRuns::metric(const std::string& name) const {
  const auto it = runs.front().metrics.find(name);
  return it == runs.front().metrics.end() ? std::nan("") : it->second;
}

NarxStudyRuns load_narx_study(const TablesOptions& o, const std::string& file) {
  const fs::path experiment = o.experiments_dir / "contour_error" / file;
  if (!fs::exists(experiment)) throw MissingResults(experiment.string() + ": not found");
  const SweepJob job = load_sweep_job(experiment, {}, o.profile);
  const SweepJobState state = sweep_job_state(job, o.results_dir);
  NarxStudyRuns out;
  out.trials = state.plan.trials.size();
  if (state.summary.missing > 0) {
    const ResultStore store(o.results_dir, o.profile);
    throw MissingResults(std::to_string(state.summary.missing) + " of " +
                         std::to_string(out.trials) + " trials of " + experiment.string() +
                         " have no result under " + state.dir.string() + "; run `" +
                         store.make_command(sweep_job_key(job, state.plan)) + "` first");
  }
  for (const auto& t : state.outcomes) {
    if (t.status != TrialOutcome::Status::complete) continue;
    const fs::path path = state.dir / t.result_file;
    const RunRecord r = read_result(path);
    if (out.runs.empty()) {
      for (const auto& net : r.narx->networks) out.axes.push_back(net.axis);
      out.train_samples = r.split.train.size();
      out.validation_samples = r.split.validation.size();
    }
    out.runs.push_back(run_of(r, path));
    out.sources.push_back(path);
  }
  if (out.runs.empty()) {
    throw MissingResults("no trial of " + experiment.string() + " completed under " +
                         state.dir.string() + " (see the .error notes there)");
  }
  return out;
}

}  // namespace cnclab
