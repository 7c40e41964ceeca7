#include "cnclab/sweep/sweep_job.hpp"

#include <yaml-cpp/yaml.h>

#include <chrono>
#include <set>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/field_schema.hpp"
#include "cnclab/core/override.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/sweep/model_search.hpp"
#include "cnclab/sweep/sweep_execute.hpp"
#include "cnclab/sweep/sweep_fields.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// results/<name>/selection.yaml: what the job selected, for people and
// scripts (cnclab reads the sweep folder itself).
std::string selection_yaml(const SweepJob& job, const SweepJobState& s) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  YAML::Emitter out;
  out << BeginMap;
  out << Key << "job" << Value << job.name;
  out << Key << "experiment" << Value << job.experiment.string();
  out << Key << "sweep_dir" << Value << s.dir.string();
  out << Key << "plan_hash" << Value << s.plan.hash();
  out << Key << "objective" << Value << YAML::Flow << BeginMap << Key << "metric" << Value
      << s.plan.objective.metric << Key << "mode" << Value
      << (s.plan.objective.maximize ? "max" : "min") << EndMap;
  out << Key << "trials" << Value << s.plan.trials.size();
  out << Key << "complete" << Value << s.summary.complete;
  out << Key << "failed" << Value << s.summary.failed + s.summary.errors;
  if (s.selected) {
    const PlannedTrial& t = s.plan.trials[*s.selected];
    out << Key << "selected" << Value << BeginMap;
    out << Key << "trial" << Value << t.id;
    out << Key << "result_file" << Value << s.selected_result().string();
    out << Key << "parameters" << Value << BeginMap;
    for (std::size_t k = 0; k < s.plan.keys.size(); ++k) {
      out << Key << s.plan.keys[k] << Value << YAML::Load(t.values[k]);
    }
    out << EndMap << Key << "metrics" << Value << BeginMap;
    for (const auto& [name, v] : s.outcomes[*s.selected].metrics) out << Key << name << Value << v;
    out << EndMap << EndMap;
  }
  out << EndMap;
  return std::string(out.c_str()) + "\n";
}

// The selection as a standard result (sweep_job.hpp, "Result").
RunRecord selection_record(const SweepJob& job, const SweepJobState& s, const fs::path& file,
                           double wall_seconds) {
  RunRecord rec = make_job_record("sweep", sweep_job_key(job, s.plan), job.request);
  rec.provenance.end_utc = utc_now_iso8601();
  rec.provenance.wall_seconds = wall_seconds;
  const auto beside = [&](const fs::path& p) {
    return p.lexically_relative(file.parent_path()).string();
  };
  rec.metrics["sweep.trials"] = static_cast<double>(s.plan.trials.size());
  rec.metrics["sweep.complete"] = static_cast<double>(s.summary.complete);
  rec.metrics["sweep.failed"] = static_cast<double>(s.summary.failed + s.summary.errors);
  rec.metrics["sweep.points"] = static_cast<double>(s.summary.points.size());
  for (const auto& [name, value] : rec.metrics) rec.metric_units[name] = "1";  // counts
  rec.facts["objective"] =
      s.plan.objective.metric + " (" + (s.plan.objective.maximize ? "max" : "min") + ")";
  rec.outputs.push_back({"summary", beside(s.dir / "summary.h5")});
  rec.outputs.push_back({"selection", "selection.yaml"});
  if (!s.selected) {
    rec.provenance.status = "failed";
    rec.provenance.failure_reason = selection_line(s);
    return rec;
  }
  const PlannedTrial& t = s.plan.trials[*s.selected];
  const fs::path trial = s.selected_result();
  rec.facts["selected_trial"] = t.id;
  rec.facts["selected_point"] = point_text(s.plan.keys, t.values);
  const RunRecord selected = read_result(trial);
  for (const auto& [name, v] : s.outcomes[*s.selected].metrics) {
    rec.metrics[name] = v;
    rec.metric_units[name] =
        selected.metric_units.contains(name) ? selected.metric_units.at(name) : "";
  }
  rec.warnings = selected.warnings;  // the selection is as degenerate as its trial
  rec.outputs.push_back({"selected_trial", beside(trial)});
  rec.upstream.push_back({job.experiment.string(), trial.string(), result_identity(selected)});
  return rec;
}

}  // namespace

ResultKey sweep_job_key(const SweepJob& job, const SweepPlan& plan) {
  return {job.name, std::nullopt, to_yaml(job) + "plan_hash: " + plan.hash() + "\n",
          job.source_file, true};
}

SweepJob load_sweep_job(const fs::path& file, const std::vector<std::string>& overrides,
                        const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  for (const auto& text : overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  if (root.get<std::string>("kind", "sweep") != "sweep") root.fail("kind", "must be sweep");
  SweepJob job;
  job.source_file = file;
  job.request = {overrides, profile};
  job.profile = profile;
  job.name = read_experiment_name(root);
  job.description = root.get<std::string>("description", "");
  sweep_job_fields().read(root, job);
  root.validate([&] { sweep_job_fields().check(job); });
  for (const auto& text : job.overrides) {
    try {
      parse_override(text);
    } catch (const ConfigError& e) {
      root.fail("overrides", e.what());
    }
  }
  try {
    job.sweep.validate();
  } catch (const ConfigError& e) {
    root.fail("sweep", e.what());
  }
  doc.check_all_consumed();
  return job;
}

std::string to_yaml(const SweepJob& job) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  YAML::Emitter out;
  out << BeginMap << Key << "kind" << Value << "sweep" << Key << "name" << Value << job.name;
  out << Key << "description" << Value << job.description;
  sweep_job_fields().emit(out, job);
  out << EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string selection_line(const SweepJobState& s) {
  const std::string counts = std::to_string(s.summary.complete) + " of " +
                             std::to_string(s.plan.trials.size()) + " trials complete";
  if (!s.selected) return "no trial selected; " + counts;
  const PlannedTrial& t = s.plan.trials[*s.selected];
  const auto& metrics = s.outcomes[*s.selected].metrics;
  const auto it = metrics.find(s.plan.objective.metric);
  return "selected " + t.id + " (" + point_text(s.plan.keys, t.values) +
         "): " + s.plan.objective.metric + " " +
         (it == metrics.end() ? std::string("?") : format_metric(it->second)) + "; " + counts;
}

fs::path SweepJobState::selected_result() const {
  if (!selected) throw Error(dir.string() + ": no complete trial to select");
  return trial_result_path(dir, plan.trials[*selected].id);
}

SweepJobState sweep_job_state(const SweepJob& job, const fs::path& results_dir) {
  SweepJobState s;
  s.plan = plan_sweep(job.experiment, job.overrides, std::nullopt, job.sweep, job.profile);
  s.dir = results_dir / job.name / ("sweep-" + s.plan.hash().substr(0, 8));
  std::error_code ec;
  if (model_based(s.plan) && fs::exists(s.dir / "summary.h5", ec)) {
    // A study's trials are in its summary (its plan is only the header).
    StoredSummary stored = read_summary(s.dir / "summary.h5");
    s.plan.trials = std::move(stored.plan.trials);
  }
  s.outcomes = read_trial_outcomes(s.dir, s.plan);
  s.summary = summarize(s.plan, s.outcomes);
  if (s.summary.best_trial >= 0) s.selected = static_cast<std::size_t>(s.summary.best_trial);
  return s;
}

SweepJobOutcome run_sweep_job(const SweepJob& job, const CommandOptions& options,
                              std::ostream* log) {
  const auto start = std::chrono::steady_clock::now();
  SweepJobOutcome r;
  r.state = sweep_job_state(job, options.results_dir);
  SweepJobState& s = r.state;
  if (!model_based(s.plan)) store_plan(s.dir, s.plan);  // a study's: run_model_search
  SweepExecuteOptions exec;
  exec.common = options;
  exec.jobs = job.jobs;
  exec.rerun = options.force;
  std::optional<SearchFindings> findings;
  if (model_based(s.plan)) {
    ModelSearch m = run_model_search(s.plan, job.sweep,
                                     {job.experiment, job.overrides, std::nullopt, job.profile},
                                     s.dir, exec, log);
    r.ran = m.ran;
    r.stopped = m.stopped;
    s.plan = std::move(m.plan);
    s.outcomes = std::move(m.outcomes);
    findings = std::move(m.findings);
  } else {
    SweepExecution ex = execute_sweep(s.plan, s.dir, exec, log);
    r.ran = ex.ran;
    r.stopped = ex.stopped;
    s.outcomes = std::move(ex.outcomes);
  }
  s.summary = summarize(s.plan, s.outcomes);
  s.selected.reset();
  if (s.summary.best_trial >= 0) s.selected = static_cast<std::size_t>(s.summary.best_trial);
  const fs::path selection = options.results_dir / job.name / "selection.yaml";
  const ResultStore store(options.results_dir, job.profile);
  const fs::path result = store.path_of(sweep_job_key(job, s.plan));
  std::error_code ec;
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (r.stopped == 0 && (r.ran > 0 || !fs::exists(s.dir / "summary.h5", ec) ||
                         !fs::exists(selection, ec) || !fs::exists(result, ec))) {
    write_summary(s.dir / "summary.h5", s.plan, s.outcomes, s.summary,
                  findings ? &*findings : nullptr);
    write_text_atomically(selection, selection_yaml(job, s));
    write_job_result(result, selection_record(job, s, result, r.wall_seconds));
  }
  if (r.stopped == 0) r.result_file = result;
  return r;
}

std::vector<JobPrework> sweep_job_prework(const SweepJob& job, const CommandOptions& options) {
  std::vector<JobPrework> out;
  std::set<std::string> seen;
  const SweepPlan plan =
      plan_sweep(job.experiment, job.overrides, std::nullopt, job.sweep, job.profile);
  for (const auto& trial : plan.trials) {
    if (!trial.experiment) continue;
    const ExperimentSpec& spec = trial.experiment->spec;
    const std::uint64_t seed = generator_seed(spec);
    const fs::path file = dataset_cache_file(spec.dataset, seed, options.datasets_dir);
    std::error_code ec;
    if (fs::exists(file, ec) || !seen.insert(file.string()).second) continue;
    out.push_back({file.string(), "dataset " + file.filename().string() + " (" + job.name + ")",
                   [dataset = spec.dataset, seed, dir = options.datasets_dir] {
                     obtain_dataset(dataset, seed, dir, nullptr);
                   }});
  }
  return out;
}

// `kind: sweep` (sweep_job.hpp): trials without a result run; a finished
// sweep with the same plan is reused.
JobKind sweep_job_kind() {
  JobKind k;
  k.kind = "sweep";
  k.summary =
      "a sweep of an experiment file, selecting the median repeat of its best point by the "
      "objective";
  k.run = [](const fs::path& file, const JobContext& c) {
    const SweepJob job = load_sweep_job(file, c.overrides, c.options.profile);
    const SweepJobOutcome r = run_sweep_job(job, c.options, c.log);
    if (r.stopped != 0) {
      throw Error(job.name + ": interrupted by signal " + std::to_string(r.stopped) +
                  "; finished trials are kept, run again to resume");
    }
    if (!r.state.selected) {
      throw Error(job.name + ": " + selection_line(r.state) + " (reasons in " +
                  (r.state.dir / "summary.h5").string() + ")");
    }
    JobReport report;
    report.name = job.name;
    report.action = r.ran == 0 ? "reused" : "ran";
    report.why = r.ran == 0 ? "sweep plan unchanged, every trial has a result"
                            : std::to_string(r.ran) + " trial(s) had no result";
    report.detail = selection_line(r.state);
    report.file = r.state.dir.string();
    return report;
  };
  k.resolved_yaml = [](const fs::path& file, const JobContext& c) {
    return to_yaml(load_sweep_job(file, c.overrides, c.options.profile));
  };
  k.prework = [](const fs::path& file, const JobContext& c) {
    return sweep_job_prework(load_sweep_job(file, c.overrides, c.options.profile), c.options);
  };
  k.profile_sources = [](const fs::path& file) {
    return std::vector<fs::path>{load_sweep_job(file).experiment};
  };
  k.schema = [] {
    return object_schema(sweep_file_fields(),
                         "kind sweep: a sweep of an experiment file and the selection of its best "
                         "point");
  };
  return k;
}

}  // namespace cnclab
