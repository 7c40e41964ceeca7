#include "cnclab/sweep/sweep_fields.hpp"

#include "cnclab/core/config.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/sweep/slurm_fields.hpp"

namespace cnclab {
namespace {

const FieldList<Objective>& objective_fields() {
  static const auto fields =
      FieldList<Objective>()
          .field("metric", &Objective::metric,
                 "a metric of the experiment's `metrics` on a split (validation.rmse); a name "
                 "without a split is its validation value; test.* is allowed with a warning "
                 "(selecting on test data)")
          .required()
          .choice("mode", &Objective::maximize, {{"min", false}, {"max", true}},
                  "min: lower is better; max: higher is better");
  return fields;
}

FieldInfo objective_info() {
  FieldInfo i = custom_info("objective",
                            "what `best` means (default: the validation value of the "
                            "experiment's first metric, min; max for r2)",
                            FieldKind::section);
  i.optional = true;
  i.children = objective_fields().info();
  return i;
}

void read_method(const ConfigReader& s, SweepSpec& spec) {
  if (!s.has("method")) return;
  const auto m = s.require<std::string>("method");
  const auto method = parse_sweep_method(m);
  if (!method) s.fail("method", "must be one of: grid, random, tpe, cmaes, nsga2, qmc");
  spec.method = *method;
}

constexpr const char* kPruners[] = {"none", "median", "successive_halving", "hyperband"};

// pruner: NAME, or {name: NAME, OPTION: integer, ...} (SweepPruner).
void read_pruner(const ConfigReader& s, SweepSpec& spec) {
  if (!s.has("pruner")) return;
  const YAML::Node node = s.raw("pruner");
  SweepPruner p;
  try {
    if (node.IsScalar()) {
      p.name = node.Scalar();
    } else if (node.IsMap() && node["name"]) {
      for (const auto& kv : node) {
        const auto key = kv.first.as<std::string>();
        if (key == "name") {
          p.name = kv.second.as<std::string>();
        } else {
          p.options[key] = kv.second.as<std::int64_t>();
        }
      }
    } else {
      s.fail("pruner", "expected a pruner name or {name: NAME, option: integer, ...}");
    }
  } catch (const YAML::Exception&) {
    s.fail("pruner", "pruner options are integers (e.g. {name: median, n_startup_trials: 5})");
  }
  bool known = false;
  for (const char* k : kPruners) known = known || p.name == k;
  if (!known) {
    s.fail("pruner",
           "'" + p.name + "' must be one of: none, median, successive_halving, hyperband");
  }
  spec.pruner = std::move(p);
}

YAML::Node pruner_node(const SweepSpec& w) {
  if (w.pruner.options.empty()) return YAML::Node(w.pruner.name);
  YAML::Node n(YAML::NodeType::Map);
  n["name"] = w.pruner.name;
  for (const auto& [k, v] : w.pruner.options) n[k] = v;
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

// sampler: {OPTION: scalar, ...} (SweepSpec::sampler).
void read_sampler(const ConfigReader& s, SweepSpec& spec) {
  if (!s.has("sampler")) return;
  const YAML::Node node = s.raw("sampler");
  if (!node.IsMap()) s.fail("sampler", "expected {option: value, ...} (e.g. {multivariate: true})");
  for (const auto& kv : node) {
    if (!kv.first.IsScalar() || !kv.second.IsScalar() || kv.second.Scalar().empty()) {
      s.fail("sampler", "each option is a name and one value (true, false, a number or a word)");
    }
    spec.sampler[kv.first.Scalar()] = kv.second.Scalar();
  }
}

YAML::Node sampler_node(const SweepSpec& w) {
  YAML::Node n(YAML::NodeType::Map);
  for (const auto& [k, v] : w.sampler) n[k] = v;
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

// objectives: [{metric: M, mode: min|max}, ...] or ["M:min", ...].
void read_objectives(const ConfigReader& s, SweepSpec& spec) {
  if (!s.has("objectives")) return;
  const YAML::Node node = s.raw("objectives");
  if (!node.IsSequence() || node.size() == 0) {
    s.fail("objectives", "expected a list of {metric, mode} or \"metric:mode\" entries");
  }
  for (const auto& item : node) {
    try {
      if (item.IsScalar()) {
        spec.objectives.push_back(parse_objective(item.Scalar()));
      } else if (item.IsMap() && item["metric"]) {
        const std::string mode = item["mode"] ? item["mode"].as<std::string>() : "min";
        spec.objectives.push_back(parse_objective(item["metric"].as<std::string>() + ":" + mode));
        for (const auto& kv : item) {
          const auto k = kv.first.as<std::string>();
          if (k != "metric" && k != "mode") throw ConfigError("unknown key '" + k + "'");
        }
      } else {
        throw ConfigError("expected {metric, mode} or \"metric:mode\"");
      }
    } catch (const ConfigError& e) {
      s.fail("objectives", e.what());
    } catch (const YAML::Exception& e) {
      s.fail("objectives", e.msg);
    }
  }
}

YAML::Node objectives_node(const SweepSpec& w) {
  YAML::Node n(YAML::NodeType::Sequence);
  for (const auto& o : w.objectives) n.push_back(o.metric + (o.maximize ? ":max" : ":min"));
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

void read_objective(const ConfigReader& s, SweepSpec& spec) {
  if (!s.has("objective")) return;
  Objective o;
  objective_fields().read(s.section("objective"), o);
  spec.objective = o;
}

// parameters: {dotted.key (k1+k2 links keys): [v1, v2, ...] | "v1,v2" |
// "log_uniform(1e-4, 1e-1)" | one value}; the grammar is sweep_spec.hpp's.
void read_parameters(const ConfigReader& s, SweepSpec& spec) {
  const ConfigReader params = s.section("parameters");
  for (const auto& key : params.keys()) {
    const YAML::Node node = params.raw(key);
    try {
      spec.set(parse_sweep_parameter(key, node));
    } catch (const ConfigError& e) {
      params.fail(key, e.what());
    }
  }
}

YAML::Node objective_node(const SweepSpec& w) {
  YAML::Node n(YAML::NodeType::Map);
  n["metric"] = w.objective->metric;
  n["mode"] = w.objective->maximize ? "max" : "min";
  n.SetStyle(YAML::EmitterStyle::Flow);
  return n;
}

YAML::Node parameters_node(const SweepSpec& w) {
  YAML::Node n(YAML::NodeType::Map);
  for (const auto& p : w.parameters) n[p.key] = p.text;
  return n;
}

}  // namespace

const FieldList<SweepSpec>& sweep_fields() {
  using S = SweepSpec;
  static const auto fields =
      FieldList<S>()
          .custom(custom_info("method",
                              "grid: every combination; random: `trials` samples (default: grid, "
                              "random when trials is given or a parameter is continuous); tpe, "
                              "cmaes, nsga2, qmc: Optuna's samplers, trials asked one by one of a "
                              "study in the sweep folder (needs python3-optuna)",
                              FieldKind::string,
                              Rule::one_of({"grid", "random", "tpe", "cmaes", "nsga2", "qmc"})),
                  read_method,
                  [](const S& w) { return YAML::Node(to_string(w.resolved_method())); })
          .field("trials", &S::trials,
                 "random search: number of points (0 with a grid); model-based: the study's "
                 "number of complete or pruned trials")
          .omit_default()
          .field("seed", &S::seed,
                 "random search and model-based: sampling seed (default: the experiment seed)")
          .field("repeats", &S::repeats,
                 "runs of each point with seeds seed, seed+1, ... (the objective takes the median)",
                 Rule::at_least(1))
          .custom(objective_info(), read_objective, objective_node,
                  [](const S& w) { return w.objective.has_value(); })
          .custom(custom_info("parameters",
                              "dotted config key (k1+k2 links keys) -> a list of values, a text "
                              "v1,v2,... or choice(...), int_range(a, b[, step]), uniform(lo, hi), "
                              "log_uniform(lo, hi)"),
                  read_parameters, parameters_node)
          .custom(custom_info("pruner",
                              "model-based methods: none | median | successive_halving | "
                              "hyperband, or {name: NAME, OPTION: integer} with Optuna's "
                              "arguments (median: n_startup_trials, n_warmup_steps, "
                              "interval_steps; successive_halving: min_resource, "
                              "reduction_factor, min_early_stopping_rate; hyperband: "
                              "min_resource, max_resource, reduction_factor)"),
                  read_pruner, pruner_node,
                  [](const S& w) { return w.pruner.name != "none" || !w.pruner.options.empty(); })
          .custom(custom_info("sampler",
                              "model-based methods: the sampler's options, {OPTION: value} with "
                              "Optuna's arguments (tpe: n_startup_trials, n_ei_candidates, "
                              "multivariate, group, constant_liar, consider_endpoints, "
                              "consider_prior, prior_weight, consider_magic_clip; cmaes: "
                              "n_startup_trials, sigma0, restart_strategy, popsize, inc_popsize, "
                              "consider_pruned_trials, use_separable_cma, with_margin; nsga2: "
                              "population_size, mutation_prob, crossover_prob, swapping_prob; "
                              "qmc: qmc_type, scramble (default true))"),
                  read_sampler, sampler_node, [](const S& w) { return !w.sampler.empty(); })
          .field("report_every", &S::report_every,
                 "model-based methods: epochs between reports of the validation objective to "
                 "the pruner",
                 Rule::at_least(1))
          .omit_default()
          .custom(custom_info("objectives",
                              "model-based methods: several objectives ([metric:mode, ...] or "
                              "[{metric, mode}, ...]); the summary lists their Pareto front, the "
                              "first ranks the points"),
                  read_objectives, objectives_node,
                  [](const S& w) { return !w.objectives.empty(); });
  return fields;
}

const FieldList<SweepJob>& sweep_job_fields() {
  using J = SweepJob;
  static const auto fields = [] {
    FieldInfo experiment = custom_info(
        "experiment", "the experiment file swept (relative to this file)", FieldKind::string);
    experiment.required = true;
    return FieldList<J>()
        .custom(
            experiment,
            [](const ConfigReader& r, J& job) {
              job.experiment_as_written = r.require<std::string>("experiment");
              job.experiment = upstream_file(r, "experiment", job.experiment_as_written,
                                             job.source_file.parent_path());
            },
            [](const J& job) { return YAML::Node(job.experiment_as_written); })
        .field("overrides", &J::overrides, "key=value settings of every trial")
        .field("jobs", &J::jobs, "trials at once (0: the cores this process may use)")
        .section("sweep", &J::sweep, sweep_fields(), "the sweep (as an experiment's sweep block)")
        .custom(
            slurm_block_info(), [](const ConfigReader& r, J&) { r.raw("slurm"); },
            [](const J&) { return YAML::Node(); }, [](const J&) { return false; });
  }();
  return fields;
}

std::vector<FieldInfo> sweep_file_fields() {
  std::vector<FieldInfo> fields = job_file_fields("sweep");
  // A named default object: with the temporary of info()'s default argument,
  // GCC 12 at -O3 warns that a string of it "may be used uninitialized".
  const SweepJob defaults;
  for (auto& f : sweep_job_fields().info(defaults)) fields.push_back(std::move(f));
  return fields;
}

}  // namespace cnclab
