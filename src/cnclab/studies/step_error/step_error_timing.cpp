#include "cnclab/studies/step_error/step_error_timing.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/units.hpp"
#include "cnclab/data/step_error.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/mlp.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// The exact method must reproduce the dataset's targets (it made them; only
// summation order could differ) and the network the result's predictions.
constexpr double kReproduceTolUm = 1e-6;
const std::vector<std::string> kSurfaces = {"surface2", "surface3"};

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// What a surface's timing needs, prepared untimed.
struct SurfaceCase {
  std::string surface;
  LoadedExperiment experiment;
  const StepErrorDatasetOptions* dataset = nullptr;  // inside experiment.spec
  std::size_t samples = 0;                           // the dataset's
  fs::path result_file;
  std::string identity;                // result_identity of that result
  std::vector<std::size_t> test;       // dataset sample indices
  std::vector<double> targets_um;      // the result's test targets
  std::vector<double> predictions_um;  // the result's test predictions
};

SurfaceCase prepare(const std::string& surface, const fs::path& file, const ResultStore& store) {
  SurfaceCase c;
  c.surface = surface;
  c.experiment = store.load(file);
  const auto* generator =
      dynamic_cast<const StepErrorGenerator*>(c.experiment.spec.dataset.generator.get());
  if (!generator) {
    throw ConfigError(file.string() + ": Table 8 timing needs a step_error dataset");
  }
  c.dataset = &generator->options();
  c.samples = generator->shape().samples;
  StoredResult stored = store.get(c.experiment);  // complete only
  c.result_file = stored.file;
  const RunRecord& r = stored.record;
  c.identity = result_identity(r);
  if (r.target_units != std::vector<std::string>{"µm"}) {
    throw Error(c.result_file.string() + ": expected one step-error target in µm");
  }
  c.test = r.split.test;
  for (std::size_t s : c.test) {
    if (s >= c.samples) throw Error(c.result_file.string() + ": test index beyond the dataset");
  }
  c.targets_um.assign(r.test_targets.data(), r.test_targets.data() + r.test_targets.size());
  c.predictions_um.assign(r.test_predictions.data(),
                          r.test_predictions.data() + r.test_predictions.size());
  return c;
}

// The tool path the dataset was made on, planned again (the shared start of the three methods).
ToolPath plan_path(const SurfaceCase& c) {
  return plan_tool_path(c.dataset->surface, c.dataset->tool_path, c.dataset->face());
}

template <class Method>
std::vector<double> step_errors_um(const SurfaceCase& c, const ToolPath& path, Method&& method) {
  std::vector<double> e(c.test.size());
  for (std::size_t i = 0; i < c.test.size(); ++i) {
    const PathSample& sample = path.samples[c.test[i]];
    e[i] = method(path.lines[sample.line].segment(sample.point)).error * kUmPerMm;
  }
  return e;
}

double max_difference(const std::vector<double>& a, const std::vector<double>& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, std::abs(a[i] - b[i]));
  return m;
}

SurfaceTiming time_surface(const SurfaceCase& c, const StepErrorTimingOptions& o) {
  SurfaceTiming t;
  t.surface = c.surface;
  t.experiment = c.experiment.spec.name;
  t.experiment_file = c.experiment.spec.source_file.string();
  t.result_file = c.result_file.string();
  t.identity = c.identity;
  t.test_samples = c.test.size();
  std::vector<double> planning, iterative, exact, load, inputs, forward;
  std::vector<double> e_iterative, e_exact, e_network;
  const std::size_t k = c.dataset->curve_points;
  for (std::size_t r = 0; r < o.repeats; ++r) {
    auto start = Clock::now();
    const ToolPath path = plan_path(c);
    planning.push_back(seconds_since(start));
    t.lines = path.lines.size();

    start = Clock::now();
    e_iterative = step_errors_um(
        c, path, [&](const StepErrorSegment& s) { return iterative_step_error(s, o.iterative); });
    iterative.push_back(seconds_since(start));

    start = Clock::now();
    e_exact = step_errors_um(
        c, path, [&](const StepErrorSegment& s) { return exact_step_error(s, c.dataset->exact); });
    exact.push_back(seconds_since(start));

    start = Clock::now();
    const RunRecord record = read_result(c.result_file);
    const Mlp mlp(record.model);
    load.push_back(seconds_since(start));

    start = Clock::now();
    Eigen::MatrixXd x(static_cast<Eigen::Index>(c.dataset->num_inputs()),
                      static_cast<Eigen::Index>(c.test.size()));
    for (std::size_t i = 0; i < c.test.size(); ++i) {
      const PathSample& sample = path.samples[c.test[i]];
      step_error_inputs(path.lines[sample.line], sample.point, k,
                        x.col(static_cast<Eigen::Index>(i)));
    }
    inputs.push_back(seconds_since(start));

    start = Clock::now();
    const Eigen::MatrixXd y = record.target_scaling.inverse_transform(
        mlp.predict(record.parameters, record.input_scaling.transform(x)));
    forward.push_back(seconds_since(start));
    e_network.assign(y.data(), y.data() + y.size());
  }
  const auto expect_reproduced = [&](const std::vector<double>& ours,
                                     const std::vector<double>& stored, const std::string& what) {
    const double difference = max_difference(ours, stored);
    if (!(difference <= kReproduceTolUm)) {
      throw Error(c.result_file.string() + ": " + what + " by " + shortest_double(difference) +
                  " µm");
    }
  };
  expect_reproduced(e_exact, c.targets_um,
                    "the exact step errors of the test segments differ from the result's targets "
                    "(test indices and tool path do not match)");
  expect_reproduced(e_network, c.predictions_um,
                    "the network's predictions from the surface differ from the result's test "
                    "predictions");
  t.planning_s = median(planning);
  t.iterative_s = median(iterative);
  t.exact_s = median(exact);
  t.network_load_s = median(load);
  t.network_inputs_s = median(inputs);
  t.network_forward_s = median(forward);
  t.iterative_max_error_um = max_difference(e_iterative, e_exact);
  t.network_max_error_um = max_difference(e_network, e_exact);
  return t;
}

}  // namespace

void StepErrorTimingOptions::validate() const {
  if (repeats < 1 || repeats > 1000) {
    throw OptionError("repeats", std::to_string(repeats), "must be in [1, 1000]");
  }
  iterative.validate();
}

const FieldList<StepErrorTimingOptions>& step_error_timing_fields() {
  using O = StepErrorTimingOptions;
  using I = IterativeStepErrorOptions;
  static const auto iterative =
      FieldList<I>()
          .field("points_per_pass", &I::points_per_pass, "CC-curve points per pass, ends included",
                 Rule::at_least(3))
          .field("relative_tolerance", &I::relative_tolerance,
                 "stop when the bracket is below this fraction of the segment's u length",
                 Rule::positive())
          .field("max_passes", &I::max_passes, "passes at most", Rule::at_least(1));
  static const auto fields =
      FieldList<O>()
          .field("repeats", &O::repeats, "timings per method; the median is reported",
                 Rule::in(1, true, 1000, true))
          .section("iterative", &O::iterative, iterative,
                   "the iterative geometric method Table 8 compares against");
  return fields;
}

std::vector<FieldInfo> step_error_timing_file_fields() {
  std::vector<FieldInfo> fields = job_file_fields("step_error_timing");
  FieldInfo experiments =
      custom_info("experiments", "the timed experiment per surface (files, relative to this one)",
                  FieldKind::section);
  experiments.required = true;
  for (const auto& surface : kSurfaces) {
    FieldInfo f = custom_info(surface, "experiment file", FieldKind::string);
    f.required = true;
    experiments.children.push_back(f);
  }
  fields.push_back(experiments);
  for (auto& f : step_error_timing_fields().info()) fields.push_back(std::move(f));
  return fields;
}

StepErrorTimingJob load_step_error_timing_job(const fs::path& file,
                                              const std::vector<std::string>& overrides,
                                              const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  for (const auto& text : overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  if (root.require<std::string>("kind") != "step_error_timing") {
    root.fail("kind", "must be step_error_timing");
  }
  StepErrorTimingJob job;
  job.source_file = file;
  job.request = {overrides, profile};
  job.profile = profile;
  job.name = read_experiment_name(root);
  job.description = root.get<std::string>("description", "");
  const ConfigReader e = root.section("experiments");
  for (const auto& surface : kSurfaces) {
    const auto text = e.require<std::string>(surface);
    job.experiments_as_written[surface] = text;
    job.experiments[surface] = resolve_config_path(e.location(surface).file, text);
  }
  step_error_timing_fields().read(root, job.options);
  root.section("iterative").validate([&] { job.options.iterative.validate(); });
  root.validate([&] { job.options.validate(); });
  doc.check_all_consumed();
  return job;
}

StepErrorTimingResult run_step_error_timing(const StepErrorTimingJob& job,
                                            const fs::path& results_dir) {
  job.options.validate();
  StepErrorTimingResult result;
  result.name = job.name;
  result.host = host_name();
  result.utc = utc_now_iso8601();
  const Provenance p = make_provenance(0);
  result.cnclab_version = p.cnclab_version;
  result.git_commit = p.git_commit;
  result.repeats = job.options.repeats;
  // Everything read first, so a missing upstream result fails before timing.
  const ResultStore store(results_dir, job.profile);
  std::vector<SurfaceCase> cases;
  for (const auto& [surface, file] : job.experiments) {
    cases.push_back(prepare(surface, file, store));
  }
  const auto start = Clock::now();
  for (const auto& c : cases) result.surfaces.push_back(time_surface(c, job.options));
  result.wall_seconds = seconds_since(start);
  return result;
}

ResultKey step_error_timing_key(const StepErrorTimingJob& job) {
  return {job.name, std::nullopt, to_yaml(job), job.source_file, true};
}

namespace {

// Per-surface figures in metric order: "<surface>.<key>", member.
const std::vector<std::pair<const char*, double SurfaceTiming::*>> kSeconds = {
    {"planning_s", &SurfaceTiming::planning_s},
    {"iterative_s", &SurfaceTiming::iterative_s},
    {"exact_s", &SurfaceTiming::exact_s},
    {"network_load_s", &SurfaceTiming::network_load_s},
    {"network_inputs_s", &SurfaceTiming::network_inputs_s},
    {"network_forward_s", &SurfaceTiming::network_forward_s},
    {"iterative_max_error_um", &SurfaceTiming::iterative_max_error_um},
    {"network_max_error_um", &SurfaceTiming::network_max_error_um},
};

}  // namespace

fs::path write_step_error_timing(const StepErrorTimingJob& job, const StepErrorTimingResult& r,
                                 const ResultStore& store) {
  const ResultKey key = step_error_timing_key(job);
  RunRecord rec = make_job_record("step_error_timing", key, job.request);
  rec.provenance.start_utc = r.utc;
  rec.provenance.end_utc = utc_now_iso8601();
  rec.provenance.wall_seconds = r.wall_seconds;
  for (const auto& s : r.surfaces) {
    for (const auto& [name, field] : kSeconds) {
      const std::string key = s.surface + "." + name;
      rec.metrics[key] = s.*field;
      rec.metric_units[key] = std::string_view(name).ends_with("_um") ? "µm" : "s";
    }
    rec.metrics[s.surface + ".test_samples"] = static_cast<double>(s.test_samples);
    rec.metrics[s.surface + ".lines"] = static_cast<double>(s.lines);
    rec.metric_units[s.surface + ".test_samples"] = rec.metric_units[s.surface + ".lines"] = "1";
    // In surface order (kSurfaces); read_step_error_timing relies on it.
    rec.upstream.push_back({s.experiment_file, s.result_file, s.identity});
    rec.facts[s.surface + ".experiment"] = s.experiment;
  }
  const fs::path file = store.path_of(key);
  write_job_result(file, rec);
  return file;
}

StepErrorTimingResult read_step_error_timing(const RunRecord& rec, const fs::path& file) {
  if (rec.kind != "step_error_timing") {
    throw IoError(file.string() + ": a " + rec.kind + " result, not a step_error_timing one");
  }
  StepErrorTimingResult r;
  r.name = rec.experiment;
  r.host = rec.provenance.host;
  r.utc = rec.provenance.start_utc;
  r.cnclab_version = rec.provenance.cnclab_version;
  r.git_commit = rec.provenance.git_commit;
  try {
    r.repeats = YAML::Load(rec.resolved_yaml)["repeats"].as<std::size_t>();
  } catch (const YAML::Exception& e) {
    throw IoError(file.string() + ": /config: no repeats (" + e.what() + ")");
  }
  const auto metric = [&](const std::string& name) {
    const auto it = rec.metrics.find(name);
    if (it == rec.metrics.end()) throw IoError(file.string() + ": no metric " + name);
    return it->second;
  };
  if (rec.upstream.size() != kSurfaces.size()) {
    throw IoError(file.string() + ": /upstream: expected one result per surface");
  }
  for (std::size_t i = 0; i < kSurfaces.size(); ++i) {
    SurfaceTiming t;
    t.surface = kSurfaces[i];
    const auto fact = rec.facts.find(t.surface + ".experiment");
    t.experiment = fact == rec.facts.end() ? "" : fact->second;
    t.experiment_file = rec.upstream[i].experiment;
    t.result_file = rec.upstream[i].result_file;
    t.identity = rec.upstream[i].identity;
    t.test_samples = static_cast<std::size_t>(metric(t.surface + ".test_samples"));
    t.lines = static_cast<std::size_t>(metric(t.surface + ".lines"));
    for (const auto& [name, field] : kSeconds) t.*field = metric(t.surface + "." + name);
    r.surfaces.push_back(t);
  }
  return r;
}

std::string to_yaml(const StepErrorTimingJob& job) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  YAML::Emitter out;
  out << BeginMap << Key << "kind" << Value << "step_error_timing";
  out << Key << "name" << Value << job.name << Key << "description" << Value << job.description;
  out << Key << "experiments" << Value << BeginMap;
  for (const auto& [surface, text] : job.experiments_as_written)
    out << Key << surface << Value << text;
  out << EndMap;
  step_error_timing_fields().emit(out, job.options);
  out << EndMap;
  return std::string(out.c_str()) + "\n";
}

std::string step_error_timing_summary(const StepErrorTimingResult& r) {
  std::string line;
  for (const auto& s : r.surfaces) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s%s: geometric %.3g s, exact %.3g s, network %.3g s",
                  line.empty() ? "" : "; ", s.surface.c_str(), s.iterative_s, s.exact_s,
                  s.network_total_s());
    line += buf;
  }
  return line;
}

}  // namespace cnclab
