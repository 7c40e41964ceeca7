#include "cnclab/sweep/model_search.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/core/field_schema.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/io/lock_file.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/sweep/optuna_helper.hpp"
#include "cnclab/sweep/trial_pool.hpp"

namespace cnclab {
namespace fs = std::filesystem;
using json = nlohmann::json;
namespace {

// Optuna's distribution of a parameter (sweep_spec.hpp's grammar).
json distribution(const SweepParameter& p) {
  json d{{"name", p.key}};
  switch (p.kind) {
    case SweepParameter::Kind::values: {
      d["type"] = "categorical";
      json choices = json::array();
      for (const auto& v : p.values) choices.push_back(node_text(v));
      d["choices"] = choices;
      break;
    }
    case SweepParameter::Kind::int_range:
      d["type"] = "int";
      d["low"] = p.first;
      d["high"] = p.first + (p.last - p.first) / p.step * p.step;  // Optuna: high on the grid
      d["step"] = p.step;
      break;
    case SweepParameter::Kind::uniform:
    case SweepParameter::Kind::log_uniform:
      d["type"] = "float";
      d["low"] = p.low;
      d["high"] = p.high;
      d["log"] = p.kind == SweepParameter::Kind::log_uniform;
      break;
  }
  return d;
}

// The YAML value of an asked parameter.
YAML::Node point_value(const SweepParameter& p, const json& v) {
  if (p.kind == SweepParameter::Kind::values) return YAML::Load(v.get<std::string>());
  if (p.kind == SweepParameter::Kind::int_range)
    return YAML::Load(std::to_string(v.get<long long>()));
  return YAML::Load(shortest_double(v.get<double>()));
}

std::uint64_t worker_index() {
  const char* task = std::getenv("SLURM_ARRAY_TASK_ID");
  return task && *task ? std::strtoull(task, nullptr, 10) : 0;
}

// One asked point: its Optuna number and its trials (repeats).
struct AskedPoint {
  long long number = 0;
  std::vector<PlannedTrial> trials;
};

const std::vector<Objective>& objectives_of(const SweepPlan& plan, std::vector<Objective>& one) {
  if (!plan.objectives.empty()) return plan.objectives;
  one = {plan.objective};
  return one;
}

// What Optuna is told of a point whose trainings ended (model_search.hpp's
// rule): pruned when repeat 0 was; complete with the mean objectives when
// every repeat completed; fail otherwise.
json tell_message(const SweepPlan& plan, long long number,
                  const std::vector<TrialOutcome>& outcomes) {
  json m{{"op", "tell"}, {"number", number}};
  if (outcomes.front().status == TrialOutcome::Status::pruned) {
    m["state"] = "pruned";
    return m;
  }
  for (const auto& o : outcomes) {
    if (o.status != TrialOutcome::Status::complete) {
      m["state"] = "fail";
      m["attrs"] = {{"cnclab_failure", to_string(o.status) + ": " + o.reason}};
      return m;
    }
  }
  std::vector<Objective> one;
  json values = json::array();
  for (const auto& objective : objectives_of(plan, one)) {
    double sum = 0;
    for (const auto& o : outcomes) sum += metric_or_nan(o.metrics, objective.metric);
    const double mean = sum / static_cast<double>(outcomes.size());
    if (!std::isfinite(mean)) {
      m["state"] = "fail";
      m["attrs"] = {{"cnclab_failure", objective.metric + " is not finite"}};
      return m;
    }
    values.push_back(mean);
  }
  m["state"] = "complete";
  m["values"] = values;
  return m;
}

// The trials of a point, in the child process: each repeat under its trial
// lock (one writer per trial, sweep_execute.hpp), skipped when a result is
// there already; repeat 0 reports to the pruner.
void train_point(const AskedPoint& point, const SweepPlan& plan, const fs::path& dir,
                 const SweepExecuteOptions& o, OptunaHelper& helper, bool prune) {
  for (const PlannedTrial& t : point.trials) {
    const LockFile lock(trial_lock_path(dir, t.id), nullptr);
    const TrialOutcome now = read_trial_outcome(dir, t);
    if (!now.done()) {
      RunOptions run;
      run.results_dir = o.common.results_dir;
      run.datasets_dir = o.common.datasets_dir;
      run.progress = ProgressMode::quiet;
      run.result_file = trial_result_path(dir, t.id);
      if (prune && t.repeat == 0) {
        run.report_metric = plan.objective.metric;
        run.report_every = plan.report_every;
        run.report = [&](std::size_t epoch, double value) {
          json m{{"op", "report"}, {"number", point.number}, {"step", epoch}};
          m["value"] = std::isfinite(value) ? json(value) : json(nullptr);
          return !helper.request(m).value("prune", false);
        };
      }
      run_experiment(*t.experiment, run);
    }
    if (t.repeat == 0 && read_trial_outcome(dir, t).status == TrialOutcome::Status::pruned) return;
  }
}

// The study's trials as a plan: each point's repeats (ids recorded in its
// user attributes), in number order; a config seen before is merged.
void realise_plan(ModelSearch& s, const json& trials, const fs::path& dir) {
  std::set<std::string> ids;
  std::size_t point = 0;
  for (const auto& t : trials) {
    const json attrs = t.value("user_attrs", json::object());
    if (!attrs.contains("cnclab_trials")) continue;  // failed before it was resolved
    const std::string state = t.value("state", "");
    bool kept = false;
    for (const auto& r : attrs["cnclab_trials"]) {
      PlannedTrial p;
      p.id = r.at("id").get<std::string>();
      p.repeat = r.at("repeat").get<std::size_t>();
      p.seed = r.at("seed").get<std::uint64_t>();
      p.values = attrs.at("cnclab_values").get<std::vector<std::string>>();
      p.point = point;
      if (!ids.insert(p.id).second) {
        ++s.plan.merged_duplicates;
        continue;
      }
      const TrialOutcome o = read_trial_outcome(dir, p);
      // A failed Optuna trial without any file of its own (a worker that
      // ended, a surplus ask) was asked again: not part of the sweep.
      if (state == "fail" && o.status == TrialOutcome::Status::missing) continue;
      kept = true;
      s.plan.trials.push_back(std::move(p));
      s.outcomes.push_back(o);
    }
    if (state == "complete" || state == "pruned") ++s.finished;
    if (kept) ++point;
  }
}

// The study's trials as a plan with their outcomes, its parameter
// importance and (several objectives) its Pareto front.
void read_findings(ModelSearch& s, OptunaHelper& helper, const SweepPlan& header,
                   const fs::path& dir) {
  realise_plan(s, helper.request({{"op", "trials"}}).at("trials"), dir);
  s.findings.importance_target = header.objective.metric;
  try {
    const json imp = helper.request({{"op", "importance"}});
    s.findings.importance_parameter = imp.at("parameter").get<std::vector<std::string>>();
    s.findings.importance_value = imp.at("value").get<std::vector<double>>();
  } catch (const Error& e) {
    s.findings.importance_note = e.what();
  }
  if (!header.objectives.empty()) {
    s.findings.multi_objective = true;
    for (const auto& objective : header.objectives) {
      s.findings.objectives += (s.findings.objectives.empty() ? "" : ", ") + objective.metric +
                               (objective.maximize ? ":max" : ":min");
    }
    const json front = helper.request({{"op", "pareto"}}).at("numbers");
    const json trials = helper.request({{"op", "trials"}}).at("trials");
    for (const auto& number : front) {
      for (const auto& t : trials) {
        if (t.at("number") != number) continue;
        const json attrs = t.value("user_attrs", json::object());
        if (attrs.contains("cnclab_trials"))
          s.findings.pareto.push_back(attrs["cnclab_trials"][0].at("id").get<std::string>());
      }
    }
  }
}

OptunaHelperOptions helper_options(const SweepPlan& header) {
  OptunaHelperOptions ho;
  ho.purpose = "sweep method " + header.method;
  return ho;
}

// The helper's message `op` with the sampler, pruner and space of `header`
// and `spec` (null: only to read a study: no space, no pruner, no options).
json study_message(const char* op, const SweepPlan& header, const SweepSpec* spec) {
  json pruner{{"name", spec ? spec->pruner.name : std::string("none")}};
  json sampler{{"name", header.method},
               {"seed", (header.sampler_seed + worker_index()) % (1ULL << 32)}};
  json params = json::array();
  if (spec) {
    for (const auto& [k, v] : spec->pruner.options) pruner[k] = v;
    for (const auto& [k, v] : spec->sampler) sampler["options"][k] = yaml_to_json(YAML::Node(v));
    for (const auto& p : spec->parameters) params.push_back(distribution(p));
  }
  return {{"op", op}, {"sampler", sampler}, {"pruner", pruner}, {"params", params}};
}

// Opens (or creates) the study of `header` in `dir`; `spec` as in
// study_message. Fails the running trials whose worker on this host has
// ended (model_search.hpp); returns the helper's answer.
json open_study(OptunaHelper& helper, const SweepPlan& header, const SweepSpec* spec,
                const fs::path& dir) {
  std::vector<Objective> one;
  json directions = json::array();
  for (const auto& objective : objectives_of(header, one))
    directions.push_back(objective.maximize ? "maximize" : "minimize");
  const std::string holder = LockFile::holder_text(static_cast<long>(::getpid()));
  const std::string host = holder.substr(0, holder.find(' '));
  json m = study_message("open", header, spec);
  m["journal"] = fs::absolute(study_journal(dir)).string();
  m["study"] = "cnclab";
  m["directions"] = directions;
  m["holder"] = {{"host", host}, {"pid", static_cast<long long>(::getpid())}};
  return helper.request(m, true);
}

}  // namespace

fs::path study_journal(const fs::path& dir) {
  return dir / "study.journal";
}

void check_study_settings(const SweepPlan& header, const SweepSpec& spec) {
  OptunaHelper helper(helper_options(header));
  helper.request(study_message("check", header, &spec), true);
}

std::size_t study_finished(const SweepPlan& header, const fs::path& dir) {
  std::error_code ec;
  if (!fs::exists(study_journal(dir), ec)) return 0;
  OptunaHelper helper(helper_options(header));
  open_study(helper, header, nullptr, dir);
  const json c = helper.request({{"op", "count"}});
  return c.at("complete").get<std::size_t>() + c.at("pruned").get<std::size_t>();
}

ModelSearch read_study(const SweepPlan& header, const fs::path& dir) {
  ModelSearch s;
  s.plan = header;
  OptunaHelper helper(helper_options(header));
  s.reaped = open_study(helper, header, nullptr, dir).at("reaped").size();
  read_findings(s, helper, header, dir);
  return s;
}

ModelSearch run_model_search(const SweepPlan& header, const SweepSpec& spec,
                             const SearchSource& source, const fs::path& dir,
                             const SweepExecuteOptions& o, std::ostream* note) {
  ModelSearch s;
  s.plan = header;
  OptunaHelper helper(helper_options(header));
  helper.request(study_message("check", header, &spec), true);  // before any file
  store_plan(dir, header);
  fs::create_directories(dir / "trials");
  s.reaped = open_study(helper, header, &spec, dir).at("reaped").size();
  if (note && s.reaped) {
    *note << "note: " << s.reaped << " trial(s) of the study were held by a worker of this host "
          << "that has ended; marked failed and asked again\n";
  }
  const bool prune = spec.pruner.name != "none";

  std::map<std::size_t, AskedPoint> running;  // by pool index
  std::size_t next_index = 0, failures = 0;
  const std::size_t max_failures = std::max<std::size_t>(spec.trials, 3);
  const auto ask = [&]() -> std::optional<TrialJob> {
    // A space where most points fail (diverge, time out) would ask forever:
    // this worker stops asking after as many failed points as trials (>= 3).
    while (failures < max_failures) {
      const json a = helper.request({{"op", "ask"}, {"limit", spec.trials}});
      if (a.at("number").is_null()) return std::nullopt;
      AskedPoint point;
      point.number = a.at("number").get<long long>();
      std::vector<YAML::Node> values;
      for (const auto& p : spec.parameters)
        values.push_back(point_value(p, a.at("params").at(p.key)));
      try {
        point.trials = resolve_point(source.experiment, source.overrides, source.seed, header.keys,
                                     values, header.repeats, source.profile);
      } catch (const ConfigError& e) {
        helper.request({{"op", "tell"},
                        {"number", point.number},
                        {"state", "fail"},
                        {"attrs", {{"cnclab_failure", e.what()}}}});
        throw;
      }
      json recorded = json::array();
      for (const auto& t : point.trials)
        recorded.push_back({{"id", t.id}, {"repeat", t.repeat}, {"seed", t.seed}});
      helper.request(
          {{"op", "attrs"},
           {"number", point.number},
           {"attrs",
            {{"cnclab_trials", recorded}, {"cnclab_values", point.trials.front().values}}}});
      std::vector<TrialOutcome> existing;
      bool all_done = true;
      for (const auto& t : point.trials) {
        existing.push_back(read_trial_outcome(dir, t));
        all_done = all_done && existing.back().done();
      }
      if (existing.front().status == TrialOutcome::Status::pruned || all_done) {
        helper.request(tell_message(header, point.number, existing));  // reused
        ++s.reused;
        if (note) {
          *note << "[study] trial " << point.number << " "
                << point_text(header.keys, point.trials.front().values)
                << ": the same config as a finished trial, its result reused\n";
        }
        continue;
      }
      const std::size_t index = next_index++;
      const PlannedTrial& first = point.trials.front();
      TrialJob job{
          index, nullptr, trial_result_path(dir, first.id), trial_error_path(dir, first.id), {}};
      running.emplace(index, std::move(point));
      const AskedPoint* asked = &running.at(index);
      job.task = [asked, &header, &dir, &o, &helper, prune] {
        train_point(*asked, header, dir, o, helper, prune);
      };
      ++s.ran;
      return job;
    }
    return std::nullopt;
  };

  PoolOptions pool;
  pool.jobs = o.jobs > 0 ? o.jobs : available_cores();
  pool.run.results_dir = o.common.results_dir;
  pool.run.datasets_dir = o.common.datasets_dir;
  pool.trial_timeout_seconds = o.trial_timeout;
  if (note) {
    *note << "sweep " << dir.string() << ": " << header.method
          << (header.sampler.empty() ? std::string() : " (" + header.sampler + ")") << " study "
          << study_journal(dir).string() << ", " << spec.trials << " trials (complete or pruned)"
          << (prune ? ", pruner " + header.pruner : std::string()) << ", " << pool.jobs
          << " job(s)\n";
  }
  s.stopped = run_trial_pool(ask, pool, [&](std::size_t index, const TrialExit& exit) {
    const AskedPoint point = std::move(running.at(index));
    running.erase(index);
    if (exit.kind == TrialExit::Kind::interrupted) return;
    std::vector<TrialOutcome> outcomes;
    for (const auto& t : point.trials) outcomes.push_back(read_trial_outcome(dir, t));
    const json tell = tell_message(header, point.number, outcomes);
    if (tell["state"] == "fail") ++failures;
    helper.request(tell);
    if (!note) return;
    *note << "[study] trial " << point.number << " "
          << point_text(header.keys, point.trials.front().values) << ": "
          << tell["state"].get<std::string>();
    if (tell.contains("values"))
      *note << " " << header.objective.metric << " "
            << format_metric(tell["values"][0].get<double>());
    if (tell.contains("attrs"))
      *note << " (" << tell["attrs"]["cnclab_failure"].get<std::string>() << ")";
    *note << "\n";
  });

  if (note && failures >= max_failures) {
    *note << "note: stopped asking after " << failures
          << " failed points (their reasons are in the lines above); run again to go on\n";
  }
  read_findings(s, helper, header, dir);
  return s;
}

}  // namespace cnclab
