#include "cnclab/sweep/sweep_plan.hpp"

#include <yaml-cpp/yaml.h>

#include <charconv>
#include <fstream>
#include <set>
#include <sstream>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kPlanFormat = "cnclab-sweep-plan";
// 2: metrics named per split ("validation.rmse"); 1: as result format 1
// (format1_metric_name, experiment/result_file.hpp), renamed when read.
constexpr int kPlanVersion = 2;

using Point = std::vector<YAML::Node>;

std::vector<Point> grid_points(const SweepSpec& spec) {
  std::vector<std::vector<YAML::Node>> axes;
  for (const auto& p : spec.parameters) axes.push_back(p.enumerate());
  std::vector<Point> points;
  std::vector<std::size_t> at(axes.size(), 0);
  while (true) {
    Point point;
    for (std::size_t k = 0; k < axes.size(); ++k) point.push_back(axes[k][at[k]]);
    points.push_back(std::move(point));
    // Odometer: the last parameter varies fastest.
    std::size_t k = axes.size();
    while (k > 0 && ++at[k - 1] == axes[k - 1].size()) at[--k] = 0;
    if (k == 0) break;
  }
  return points;
}

std::vector<Point> random_points(const SweepSpec& spec, std::uint64_t seed) {
  std::vector<Point> points;
  for (std::size_t s = 0; s < spec.trials; ++s) {
    Point point;
    for (const auto& p : spec.parameters) {
      Rng rng(seed, "sweep/" + p.key + "/" + std::to_string(s));
      point.push_back(p.sample(rng));
    }
    points.push_back(std::move(point));
  }
  return points;
}

Override override_of(const std::string& key, const YAML::Node& value) {
  Override o = parse_override(key + "=0");
  o.value = YAML::Clone(value);
  o.text = key + "=" + node_text(value);
  return o;
}

}  // namespace

std::string point_text(const std::vector<std::string>& keys, const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t k = 0; k < keys.size(); ++k) s += (k ? " " : "") + keys[k] + "=" + v[k];
  return s;
}

std::string SweepPlan::to_yaml() const {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  YAML::Emitter out;
  out << BeginMap;
  out << Key << "format" << Value << kPlanFormat;
  out << Key << "format_version" << Value << kPlanVersion;
  out << Key << "experiment" << Value << experiment;
  out << Key << "method" << Value << method;
  out << Key << "repeats" << Value << repeats;
  out << Key << "objective" << Value << YAML::Flow << BeginMap << Key << "metric" << Value
      << objective.metric << Key << "mode" << Value << (objective.maximize ? "max" : "min")
      << EndMap;
  out << Key << "keys" << Value << YAML::Flow << keys;
  out << Key << "metrics" << Value << YAML::Flow << metrics;
  out << Key << "merged_duplicates" << Value << merged_duplicates;
  if (model_based(*this)) {
    out << Key << "space" << Value << YAML::Flow << YAML::DoubleQuoted << space;
    out << Key << "sampler_seed" << Value << sampler_seed;
    out << Key << "pruner" << Value << pruner;
    if (!sampler.empty()) out << Key << "sampler" << Value << sampler;
    out << Key << "report_every" << Value << report_every;
    if (!objectives.empty()) {
      out << Key << "objectives" << Value << YAML::Flow << YAML::BeginSeq;
      for (const auto& o : objectives) out << o.metric + (o.maximize ? ":max" : ":min");
      out << YAML::EndSeq;
    }
  }
  out << Key << "trials" << Value << YAML::BeginSeq;
  for (const auto& t : trials) {
    out << YAML::Flow << BeginMap;
    out << Key << "id" << Value << t.id;
    out << Key << "point" << Value << t.point;
    out << Key << "repeat" << Value << t.repeat;
    out << Key << "seed" << Value << t.seed;
    out << Key << "values" << Value << YAML::Flow << YAML::DoubleQuoted << t.values;
    out << EndMap;
  }
  out << YAML::EndSeq << EndMap;
  return std::string(out.c_str()) + "\n";
}

bool model_based(const SweepPlan& plan) {
  const auto m = parse_sweep_method(plan.method);
  return m && model_based(*m);
}

std::string SweepPlan::hash() const {
  return hash_hex(to_yaml());
}

Objective resolve_objective(const std::optional<Objective>& given,
                            const std::vector<std::string>& selection) {
  if (given) {
    Objective o = *given;
    if (o.metric == kOlderValidationMse) {
      o.metric = metric_name("validation", "normalised_mse");
    } else if (metric_split(o.metric).empty()) {
      o.metric = metric_name("validation", o.metric);
    }
    return o;
  }
  if (selection.empty()) throw ConfigError("sweep: the experiment lists no metrics to rank by");
  const std::string& first = selection.front();
  const std::string base = first == kOlderValidationMse ? "normalised_mse" : metric_base(first);
  return {metric_name("validation", base), base == "r2"};
}

std::string objective_warning(const SweepPlan& plan) {
  if (metric_split(plan.objective.metric) != "test") return "";
  return "the objective " + plan.objective.metric +
         " ranks the points by the test split: the point is chosen on test data, so its test "
         "metrics are no estimate of new data (rank by a validation metric, the default, and "
         "report test once, after)";
}

SweepPlan plan_sweep(const fs::path& file, const std::vector<std::string>& overrides,
                     std::optional<std::uint64_t> seed, const SweepSpec& spec,
                     const std::string& profile) {
  spec.validate();
  const LoadedExperiment base = load_experiment(file, overrides, seed, profile);
  SweepPlan plan;
  plan.experiment = base.spec.name;
  plan.method = to_string(spec.resolved_method());
  plan.repeats = spec.repeats;
  plan.metrics = stored_metrics(base.spec);
  plan.objective = resolve_objective(
      spec.objectives.empty() ? spec.objective : spec.objectives.front(), base.spec.metrics);
  if (spec.objectives.size() > 1) {
    for (const auto& o : spec.objectives) {
      plan.objectives.push_back(resolve_objective(o, base.spec.metrics));
      const std::string& m = plan.objectives.back().metric;
      if (std::find(plan.metrics.begin(), plan.metrics.end(), m) == plan.metrics.end()) {
        throw ConfigError("sweep: objectives: metric '" + m +
                          "' is not among the experiment's metrics");
      }
    }
  }
  if (std::find(plan.metrics.begin(), plan.metrics.end(), plan.objective.metric) ==
      plan.metrics.end()) {
    std::string known;
    for (const auto& m : plan.metrics) known += (known.empty() ? "" : ", ") + m;
    const std::string split = metric_split(plan.objective.metric);
    const auto splits = metric_splits_of(base.spec);
    const bool no_split = std::find(splits.begin(), splits.end(), split) == splits.end();
    throw ConfigError(
        "sweep: objective metric '" + plan.objective.metric + "' is not among the experiment's " +
        "metrics (" + known + ")" +
        (no_split ? "; the experiment has no " + split + " split" +
                        (split == "validation"
                             ? " (a sweep ranks by a validation metric unless told otherwise: "
                               "give the experiment one, e.g. split.validation=0.1, or name "
                               "the objective)"
                             : "")
                  : ""));
  }
  for (const auto& p : spec.parameters) plan.keys.push_back(p.key);
  if (model_based(spec.resolved_method())) {
    // The study asks the points (model_search.hpp); the plan is its header.
    for (const auto& p : spec.parameters) plan.space.push_back(p.key + "=" + p.text);
    plan.sampler_seed = spec.seed.value_or(base.spec.seed);
    plan.pruner = spec.pruner.name;
    for (const auto& [k, v] : spec.pruner.options) plan.pruner += " " + k + "=" + std::to_string(v);
    for (const auto& [k, v] : spec.sampler)
      plan.sampler += (plan.sampler.empty() ? "" : " ") + k + "=" + v;
    plan.report_every = spec.report_every;
    return plan;
  }

  const std::vector<Point> points = spec.resolved_method() == SweepMethod::grid
                                        ? grid_points(spec)
                                        : random_points(spec, spec.seed.value_or(base.spec.seed));
  std::set<std::string> ids;
  std::size_t next_point = 0;
  for (const Point& point : points) {
    bool kept = false;
    for (PlannedTrial& t :
         resolve_point(file, overrides, seed, plan.keys, point, spec.repeats, profile)) {
      if (!ids.insert(t.id).second) {
        ++plan.merged_duplicates;
        continue;
      }
      kept = true;
      t.point = next_point;
      plan.trials.push_back(std::move(t));
    }
    if (kept) ++next_point;
  }
  return plan;
}

std::vector<PlannedTrial> resolve_point(const fs::path& file,
                                        const std::vector<std::string>& overrides,
                                        std::optional<std::uint64_t> seed,
                                        const std::vector<std::string>& keys,
                                        const std::vector<YAML::Node>& point, std::size_t repeats,
                                        const std::string& profile) {
  std::vector<Override> trial_overrides;
  for (const auto& text : overrides) trial_overrides.push_back(parse_override(text));
  std::vector<std::string> values;
  for (std::size_t k = 0; k < point.size(); ++k) {
    for (const auto& key : linked_keys(keys[k])) {
      trial_overrides.push_back(override_of(key, point[k]));
    }
    values.push_back(node_text(point[k]));
  }
  const auto load = [&](std::optional<std::uint64_t> trial_seed) {
    try {
      return load_experiment(file, trial_overrides, trial_seed, profile);
    } catch (const ConfigError& e) {
      throw ConfigError("sweep trial " + point_text(keys, values) + ": " + e.what());
    }
  };
  std::vector<PlannedTrial> trials;
  std::uint64_t point_seed = 0;
  for (std::size_t r = 0; r < repeats; ++r) {
    PlannedTrial t;
    t.repeat = r;
    t.values = values;
    t.experiment =
        r == 0 ? load(seed) : load(derive_seed(point_seed, "repeat/" + std::to_string(r)));
    if (r == 0) point_seed = t.experiment->spec.seed;
    t.seed = t.experiment->spec.seed;
    t.id = hash_hex(t.experiment->resolved_yaml);
    trials.push_back(std::move(t));
  }
  return trials;
}

std::vector<std::size_t> shard_trials(std::size_t trial_count, std::size_t shard,
                                      std::size_t shards) {
  std::vector<std::size_t> out;
  for (std::size_t i = shard - 1; i < trial_count; i += shards) out.push_back(i);
  return out;
}

std::pair<std::size_t, std::size_t> parse_shard(const std::string& text) {
  const auto slash = text.find('/');
  std::size_t k = 0, n = 0;
  const auto parse = [](std::string_view s, std::size_t& v) {
    const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    return ec == std::errc() && ptr == s.data() + s.size() && !s.empty();
  };
  if (slash == std::string::npos || !parse(std::string_view(text).substr(0, slash), k) ||
      !parse(std::string_view(text).substr(slash + 1), n)) {
    throw ConfigError("--shard " + text + ": expected K/N, e.g. 2/8 (shard K of N, 1 <= K <= N)");
  }
  if (n < 1 || k < 1 || k > n) {
    throw ConfigError("--shard " + text + ": K must be between 1 and N (got K = " +
                      std::to_string(k) + ", N = " + std::to_string(n) + ")");
  }
  return {k, n};
}

fs::path trial_result_path(const fs::path& dir, const std::string& id) {
  return dir / "trials" / (id + ".h5");
}

fs::path trial_error_path(const fs::path& dir, const std::string& id) {
  return dir / "trials" / (id + ".error");
}

fs::path trial_lock_path(const fs::path& dir, const std::string& id) {
  std::string name = ".";  // appended: GCC 12 warns falsely on "." + id (-Wrestrict, PR105329)
  name += id;
  name += ".lock";
  return dir / "trials" / name;
}

void store_plan(const fs::path& dir, const SweepPlan& plan) {
  const fs::path path = dir / "sweep.yaml";
  const std::string text = plan.to_yaml();
  std::error_code ec;
  if (fs::exists(path, ec)) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    if (ss.str() == text) return;
    throw ConfigError(dir.string() + " holds another sweep (its sweep.yaml lists other trials); " +
                      "choose another --dir or remove that folder");
  }
  AtomicOutput out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << text;
    f.close();
    if (!f) throw IoError(path.string() + ": cannot write the sweep plan");
  }
  out.commit();
}

namespace {

// The plan in a sweep.yaml document (load_plan, parse_plan).
SweepPlan plan_from(const ConfigDocument& doc, const std::string& origin) {
  try {
    const ConfigReader r = doc.root();
    if (r.get<std::string>("format", "") != kPlanFormat) {
      r.fail("format", std::string("not a sweep plan (expected ") + kPlanFormat + ")");
    }
    const auto version = r.require<std::int64_t>("format_version");
    r.check(version == 1 || version == kPlanVersion, "format_version", "unsupported version");
    SweepPlan plan;
    plan.experiment = r.require<std::string>("experiment");
    plan.method = r.require<std::string>("method");
    plan.repeats = r.require<std::size_t>("repeats");
    const ConfigReader o = r.section("objective");
    plan.objective.metric = o.require<std::string>("metric");
    plan.objective.maximize = o.require<std::string>("mode") == "max";
    plan.keys = r.require<std::vector<std::string>>("keys");
    plan.metrics = r.require<std::vector<std::string>>("metrics");
    plan.merged_duplicates = r.require<std::size_t>("merged_duplicates");
    if (model_based(plan)) {
      plan.space = r.require<std::vector<std::string>>("space");
      plan.sampler_seed = r.require<std::uint64_t>("sampler_seed");
      plan.pruner = r.require<std::string>("pruner");
      plan.sampler = r.get<std::string>("sampler", "");
      plan.report_every = r.require<std::size_t>("report_every");
      for (const auto& o : r.get<std::vector<std::string>>("objectives", {}))
        plan.objectives.push_back(parse_objective(o));
    }
    if (version == 1) {
      plan.objective.metric = format1_metric_name(plan.objective.metric);
      for (auto& m : plan.metrics) m = format1_metric_name(m);
    }
    const YAML::Node trials = r.raw("trials");
    if (!trials.IsSequence()) r.fail("trials", "expected a list");
    for (const auto& node : trials) {
      PlannedTrial t;
      t.id = node["id"].as<std::string>();
      t.point = node["point"].as<std::size_t>();
      t.repeat = node["repeat"].as<std::size_t>();
      t.seed = node["seed"].as<std::uint64_t>();
      t.values = node["values"].as<std::vector<std::string>>();
      if (t.values.size() != plan.keys.size()) r.fail("trials", "values do not match keys");
      plan.trials.push_back(std::move(t));
    }
    doc.check_all_consumed();
    return plan;
  } catch (const ConfigError& e) {
    throw IoError(std::string("sweep plan unreadable: ") + e.what());
  } catch (const YAML::Exception& e) {
    throw IoError(origin + ": sweep plan unreadable: " + e.msg);
  }
}

}  // namespace

SweepPlan load_plan(const fs::path& dir) {
  const fs::path path = dir / "sweep.yaml";
  try {
    return plan_from(ConfigDocument::load(path), path.string());
  } catch (const ConfigError& e) {
    throw IoError(std::string("sweep plan unreadable: ") + e.what());
  } catch (const YAML::Exception& e) {
    throw IoError(path.string() + ": sweep plan unreadable: " + e.msg);
  }
}

SweepPlan parse_plan(const std::string& yaml_text, const std::string& origin) {
  try {
    return plan_from(ConfigDocument::parse(yaml_text, origin), origin);
  } catch (const ConfigError& e) {
    throw IoError(std::string("sweep plan unreadable: ") + e.what());
  } catch (const YAML::Exception& e) {
    throw IoError(origin + ": sweep plan unreadable: " + e.msg);
  }
}

}  // namespace cnclab
