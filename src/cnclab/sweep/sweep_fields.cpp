#include "cnclab/sweep/sweep_fields.hpp"

#include "cnclab/core/config.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/sweep/slurm_fields.hpp"

namespace cnclab {
namespace {

const char* method_name(SweepMethod m) {
  return m == SweepMethod::grid ? "grid" : "random";
}

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
  if (m != "grid" && m != "random") s.fail("method", "must be one of: grid, random");
  spec.method = m == "grid" ? SweepMethod::grid : SweepMethod::random;
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
                              "random when trials is given or a parameter is continuous)",
                              FieldKind::string, Rule::one_of({"grid", "random"})),
                  read_method,
                  [](const S& w) { return YAML::Node(method_name(w.resolved_method())); })
          .field("trials", &S::trials, "random search: number of points (0 with a grid)")
          .omit_default()
          .field("seed", &S::seed, "random search: sampling seed (default: the experiment seed)")
          .field("repeats", &S::repeats,
                 "runs of each point with seeds seed, seed+1, ... (the objective takes the median)",
                 Rule::at_least(1))
          .custom(objective_info(), read_objective, objective_node,
                  [](const S& w) { return w.objective.has_value(); })
          .custom(custom_info("parameters",
                              "dotted config key (k1+k2 links keys) -> a list of values, a text "
                              "v1,v2,... or choice(...), int_range(a, b[, step]), uniform(lo, hi), "
                              "log_uniform(lo, hi)"),
                  read_parameters, parameters_node);
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
  for (auto& f : sweep_job_fields().info()) fields.push_back(std::move(f));
  return fields;
}

}  // namespace cnclab
