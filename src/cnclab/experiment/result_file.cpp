#include "cnclab/experiment/result_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>

#include "cnclab/core/config_abbreviate.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_inference.hpp"
#include "cnclab/experiment/result_lm_history.hpp"
#include "cnclab/experiment/result_narx.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/experiment/trainer_spec.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/eigen_std.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/isolated_read.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

void write_scaling(H5File& f, const std::string& g, const ScalingRecord& s,
                   const std::string& units) {
  f.create_group(g);
  f.set_attribute(g, "method", to_string(s.method));
  if (s.method == Scaling::zscore) {
    f.write_vector(g + "/mean", to_std(s.mean), units);
    f.write_vector(g + "/std", to_std(s.std), units);
  } else if (s.method == Scaling::minmax) {
    // y = (y_max - y_min) (x - min) / (max - min) + y_min; constant features
    // (min = max): y = x.
    f.set_attribute(g, "formula", "mapminmax to [y_min, y_max]");
    f.set_attribute(g, "y_min", s.y_min);
    f.set_attribute(g, "y_max", s.y_max);
    f.write_vector(g + "/min", to_std(s.min), units);
    f.write_vector(g + "/max", to_std(s.max), units);
  }
}

ScalingRecord read_scaling(const H5File& f, const std::string& g) {
  ScalingRecord s;
  const std::string method = f.attribute_string(g, "method");
  if (!parse_scaling(method, s.method)) {
    throw IoError(f.path().string() + ": " + g + ": unknown scaling method '" + method + "'");
  }
  if (s.method == Scaling::zscore) {
    s.mean = to_eigen(f.read_vector(g + "/mean"));
    s.std = to_eigen(f.read_vector(g + "/std"));
  } else if (s.method == Scaling::minmax) {
    s.min = to_eigen(f.read_vector(g + "/min"));
    s.max = to_eigen(f.read_vector(g + "/max"));
    // Results written before the range was configurable used [-1, 1].
    if (f.has_attribute(g, "y_min")) s.y_min = f.attribute_double(g, "y_min");
    if (f.has_attribute(g, "y_max")) s.y_max = f.attribute_double(g, "y_max");
  }
  return s;
}

void write_mlp_sections(H5File& f, const RunRecord& r) {
  f.create_group("/model");
  f.set_attribute("/model", "type", "mlp");
  std::vector<double> sizes;
  sizes.push_back(static_cast<double>(r.model.inputs));
  for (auto h : r.model.hidden) sizes.push_back(static_cast<double>(h));
  sizes.push_back(static_cast<double>(r.model.outputs));
  f.write_vector("/model/layer_sizes", sizes, "1");
  f.set_attribute("/model", "hidden_activation", to_string(r.model.hidden_activation));
  f.set_attribute("/model", "output_activation", to_string(r.model.output_activation));
  f.set_attribute("/model", "dropout_keep_probability", r.model.dropout_keep_probability);
  f.set_attribute("/model", "dropout_placement", to_string(r.model.dropout_placement));
  write_inference(f, r);
  f.set_attribute("/model", "parameter_layout",
                  "per layer: W (n_out x n_in, column-major) then b (n_out)");
  f.write_vector("/model/parameters", to_std(r.parameters), "1");
  write_scaling(f, "/model/input_scaling", r.input_scaling, join(r.input_units, ","));
  write_scaling(f, "/model/target_scaling", r.target_scaling, join(r.target_units, ","));

  f.create_group("/training");
  f.set_attribute("/training", "trainer", r.trainer);
  f.set_attribute("/training", "termination", to_string(r.training.termination));
  f.set_attribute("/training", "message", r.training.message);
  f.set_attribute("/training", "best_epoch", static_cast<std::int64_t>(r.training.best_epoch));
  std::vector<double> epoch, train, val, wall;
  for (const auto& e : r.training.history) {
    epoch.push_back(static_cast<double>(e.epoch));
    train.push_back(e.train_loss);
    val.push_back(e.validation_loss);
    wall.push_back(e.wall_seconds);
  }
  f.write_vector("/history/epoch", epoch, "1");
  f.write_vector("/history/train_loss", train, "normalised MSE");
  f.write_vector("/history/validation_loss", val, "normalised MSE");
  f.write_vector("/history/test_loss", r.test_loss, "normalised MSE");
  f.write_vector("/history/wall_seconds", wall, "s");
  const TrainerDef* trainer = trainers().find(r.trainer);
  if (trainer && trainer->history != TrainerHistory::epochs) {
    f.set_attribute("/training", "beta_guard_count",
                    static_cast<std::int64_t>(r.training.beta_guard_count));
    write_lm_history(f, "/history", r.training);
  }

  const std::string target_units = join(r.target_units, ",");
  f.write_matrix("/test/predictions", r.test_predictions, target_units);
  f.write_matrix("/test/targets", r.test_targets, target_units);
}

}  // namespace

void write_result(const fs::path& path, const RunRecord& r) {
  AtomicOutput out(path);
  try {
    H5File f = H5File::create(out.temp_path());
    write_result_header(f, r);

    f.create_group("/dataset");
    f.set_attribute("/dataset", "file", r.dataset_file);
    f.set_attribute("/dataset", "content_hash", r.dataset_hash);
    f.write_strings("/dataset/input_names", r.input_names);
    f.write_strings("/dataset/input_units", r.input_units);
    f.write_strings("/dataset/target_names", r.target_names);
    f.write_strings("/dataset/target_units", r.target_units);

    f.write_indices("/split/train", r.split.train);
    f.write_indices("/split/validation", r.split.validation);
    f.write_indices("/split/test", r.split.test);

    if (r.narx) {
      write_narx_sections(f, r);
    } else {
      write_mlp_sections(f, r);
    }

    write_metrics(f, r.metrics, training_metric_units(r));

    write_result_upstream(f, r.upstream);

    mark_complete(f);  // last
    f.close();
    out.commit();
  } catch (const IoError& e) {
    // Name the file the user asked for; the temporary is removed by `out`.
    throw IoError(path.string() + ": result not written: " + std::string(e.what()));
  }
}

void write_result_header(H5File& f, const RunRecord& r) {
  write_format(f, kResultFormat, kResultFormatVersion);
  if (r.kind != "train") f.set_attribute("/", "kind", r.kind);  // absent: train
  f.set_attribute("/", "experiment", r.experiment);
  f.set_attribute("/", "config_hash", r.config_hash);
  f.set_attribute("/", "status", r.provenance.status);
  if (!r.warnings.empty()) f.set_attribute("/", "warnings", join_warnings(r.warnings));
  f.write_string("/config", r.resolved_yaml);
  write_provenance(f, "/provenance", r.provenance);
}

void print_metrics(const RunRecord& r, const std::string& note, std::ostream& out) {
  std::size_t name_width = 14, value_width = 0;
  for (const auto& [name, value] : r.metrics) {
    name_width = std::max(name_width, name.size() + 2);
    value_width = std::max(value_width, format_metric(value).size() + 2);
  }
  out << "metrics" << (note.empty() ? "" : "      (" + note + ")") << "\n";
  // Split by split (train, validation, test), then names without a split.
  std::vector<std::pair<std::string, double>> ordered(r.metrics.begin(), r.metrics.end());
  const auto rank = [](const std::string& name) {
    const auto& splits = metric_splits();
    return std::find(splits.begin(), splits.end(), metric_split(name)) - splits.begin();
  };
  std::stable_sort(ordered.begin(), ordered.end(),
                   [&](const auto& a, const auto& b) { return rank(a.first) < rank(b.first); });
  for (const auto& [name, value] : ordered) {
    const auto it = r.metric_units.find(name);
    const std::string unit = it == r.metric_units.end() ? "" : it->second;
    std::string line = "  " + name + std::string(name_width - name.size(), ' ') +
                       format_metric(value) +
                       std::string(value_width - format_metric(value).size(), ' ') +
                       (unit == "1" ? "1 (dimensionless)" : unit);
    while (!line.empty() && line.back() == ' ') line.pop_back();
    out << line << "\n";
  }
}

void print_result_config(const std::string& resolved_yaml, std::ostream& out,
                         const ShowOptions& options) {
  const AbbreviatedConfig shown =
      options.full_config ? AbbreviatedConfig{resolved_yaml, 0} : abbreviate_config(resolved_yaml);
  out << "config";
  if (shown.abbreviated > 0) {
    out << " (" << shown.abbreviated << " array(s) of more than " << kAbbreviateScalars
        << " numbers abbreviated; --full prints them)";
  }
  out << "\n";
  const std::string& text = shown.text;
  std::size_t start = 0;
  while (start < text.size()) {
    const auto end = text.find('\n', start);
    out << "  " << text.substr(start, end - start) << "\n";
    if (end == std::string::npos) break;
    start = end + 1;
  }
}

void write_result_upstream(H5File& f, const std::vector<UpstreamRef>& upstream) {
  if (upstream.empty()) return;
  std::vector<std::string> experiments, files, identities;
  for (const auto& u : upstream) {
    experiments.push_back(u.experiment);
    files.push_back(u.result_file);
    identities.push_back(u.identity);
  }
  f.write_strings("/upstream/experiments", experiments);
  f.write_strings("/upstream/result_files", files);
  f.write_strings("/upstream/identities", identities);
}

void write_metrics(H5File& f, const std::map<std::string, double>& metrics,
                   const std::map<std::string, std::string>& units) {
  // Numbers only in /metrics, so {k: float(v) for k, v in f["metrics"].attrs.items()}
  // works in h5py; the units beside them.
  f.create_group("/metrics");
  for (const auto& [name, value] : metrics) f.set_attribute("/metrics", name, value);
  f.create_group("/metrics/units");
  for (const auto& [name, value] : metrics) {
    const auto it = units.find(name);
    f.set_attribute("/metrics/units", name, it == units.end() ? "" : it->second);
  }
}

std::map<std::string, std::string> read_metric_units(const H5File& f) {
  std::map<std::string, std::string> units;
  if (!f.is_group("/metrics/units")) return units;
  for (const auto& name : f.attribute_names("/metrics/units")) {
    units[name] = f.attribute_string("/metrics/units", name);
  }
  return units;
}

std::map<std::string, std::string> training_metric_units(const RunRecord& r) {
  std::map<std::string, std::string> units;
  for (const auto& [name, value] : r.metrics) {
    units[name] =
        r.narx ? sequence_metric_unit(metric_base(name)) : metric_unit(name, r.target_units);
  }
  return units;
}

std::map<std::string, double> read_metrics(const H5File& f) {
  std::map<std::string, double> metrics;
  for (const auto& name : f.attribute_names("/metrics")) {
    if (name != "units") metrics[name] = f.attribute_double("/metrics", name);
  }
  return metrics;
}

std::string format1_metric_name(const std::string& name) {
  if (name == kOlderValidationMse) return metric_name("validation", "normalised_mse");
  if (!metric_split(name).empty()) return name;
  const auto& mlp = base_metrics();
  const bool of_test = std::find(mlp.begin(), mlp.end(), name) != mlp.end();
  return metric_name(of_test ? "test" : "validation", name);
}

namespace {
bool is_training_result(const H5File& f) {
  return !f.has_attribute("/", "kind") || f.attribute_string("/", "kind") == "train";
}

// Metrics (or their units) of file `f` of format `version` under today's
// names: every name of a training result; of a job result only the training
// metrics it carries (a sweep job's selected trial: base metrics, the older
// validation name, registered sequence metrics), not the job's own names.
template <class V>
std::map<std::string, V> current_names(std::map<std::string, V> stored, const H5File& f,
                                       int version) {
  if (version >= 2) return stored;
  const bool training = is_training_result(f);
  const auto& mlp = base_metrics();
  const auto sequence = sequence_metric_names();
  const auto renamed = [&](const std::string& name) {
    const bool of_training = training || name == kOlderValidationMse ||
                             std::find(mlp.begin(), mlp.end(), name) != mlp.end() ||
                             std::find(sequence.begin(), sequence.end(), name) != sequence.end();
    return of_training ? format1_metric_name(name) : name;
  };
  std::map<std::string, V> out;
  for (auto& [name, value] : stored) out[renamed(name)] = std::move(value);
  return out;
}
}  // namespace

std::vector<std::string> read_warnings(const H5File& f) {
  if (!f.has_attribute("/", "warnings")) return {};
  return split_warnings(f.attribute_string("/", "warnings"));
}

std::vector<UpstreamRef> read_upstream(const H5File& f) {
  std::vector<UpstreamRef> out;
  if (!f.exists("/upstream")) return out;
  const auto experiments = f.read_strings("/upstream/experiments");
  const auto files = f.read_strings("/upstream/result_files");
  const auto identities = f.read_strings("/upstream/identities");
  if (files.size() != experiments.size() || identities.size() != experiments.size()) {
    throw IoError(f.path().string() + ": /upstream: lists of different lengths");
  }
  for (std::size_t i = 0; i < experiments.size(); ++i) {
    out.push_back({experiments[i], files[i], identities[i]});
  }
  return out;
}

namespace {

RunRecord read_result_in_process(const std::filesystem::path& path);

ResultStatus read_status_in_process(const std::filesystem::path& path) {
  const H5File f = H5File::open_read(path);
  const int version =
      require_format(f, kResultFormat, kResultOldestFormatVersion, kResultFormatVersion);
  ResultStatus s;
  s.status = f.attribute_string("/", "status");
  s.failure_reason = f.attribute_string("/provenance", "failure_reason");
  s.metrics = current_names(read_metrics(f), f, version);
  s.metric_units = current_names(read_metric_units(f), f, version);
  s.warnings = read_warnings(f);
  s.upstream = read_upstream(f);
  return s;
}

}  // namespace

ResultStatus read_result_status(const std::filesystem::path& path) {
  probe_in_child(path, [&] { read_status_in_process(path); });
  return read_status_in_process(path);
}

RunRecord read_result(const std::filesystem::path& path) {
  probe_in_child(path, [&] { read_result_in_process(path); });
  return read_result_in_process(path);
}

namespace {
void read_mlp_sections(const H5File& f, RunRecord& r) {
  const auto& path = f.path();
  const auto bad = [&](const std::string& what) { throw IoError(path.string() + ": " + what); };
  const auto sizes = f.read_vector("/model/layer_sizes");
  if (sizes.size() < 2) bad("/model/layer_sizes: needs at least 2 entries");
  r.model.inputs = static_cast<std::size_t>(sizes.front());
  r.model.outputs = static_cast<std::size_t>(sizes.back());
  r.model.hidden.clear();
  for (std::size_t i = 1; i + 1 < sizes.size(); ++i)
    r.model.hidden.push_back(static_cast<std::size_t>(sizes[i]));
  try {
    r.model.hidden_activation = parse_activation(f.attribute_string("/model", "hidden_activation"));
    r.model.output_activation = parse_activation(f.attribute_string("/model", "output_activation"));
  } catch (const OptionError& e) {
    bad(std::string("/model: ") + e.what());
  }
  r.model.dropout_keep_probability = f.attribute_double("/model", "dropout_keep_probability");
  // Read back so that Mlp(r.model) has the run's dropout layers (MC dropout).
  if (f.has_attribute("/model", "dropout_placement")) {
    const std::string placement = f.attribute_string("/model", "dropout_placement");
    if (placement == to_string(DropoutPlacement::after_every_hidden)) {
      r.model.dropout_placement = DropoutPlacement::after_every_hidden;
    } else if (placement != to_string(DropoutPlacement::between_hidden)) {
      bad("/model: unknown dropout_placement '" + placement + "'");
    }
  }
  read_inference(f, r);
  r.parameters = to_eigen(f.read_vector("/model/parameters"));
  r.input_scaling = read_scaling(f, "/model/input_scaling");
  r.target_scaling = read_scaling(f, "/model/target_scaling");

  const std::string termination = f.attribute_string("/training", "termination");
  if (!parse_termination(termination, r.training.termination)) {
    bad("/training: unknown termination '" + termination + "'");
  }
  r.trainer = f.attribute_string("/training", "trainer");
  const TrainerDef* trainer = trainers().find(r.trainer);
  if (trainer == nullptr) bad("/training: unknown trainer '" + r.trainer + "'");
  r.training.message = f.attribute_string("/training", "message");
  r.training.best_epoch = static_cast<std::size_t>(f.attribute_int("/training", "best_epoch"));
  const auto epoch = f.read_vector("/history/epoch");
  const auto train = f.read_vector("/history/train_loss");
  const auto val = f.read_vector("/history/validation_loss");
  const auto wall = f.read_vector("/history/wall_seconds");
  if (train.size() != epoch.size() || val.size() != epoch.size() || wall.size() != epoch.size()) {
    bad("/history: series of different lengths");
  }
  for (std::size_t i = 0; i < epoch.size(); ++i) {
    r.training.history.push_back({static_cast<std::size_t>(epoch[i]), train[i], val[i], wall[i]});
  }
  if (trainer->history != TrainerHistory::epochs) {
    r.training.beta_guard_count =
        static_cast<std::size_t>(f.attribute_int("/training", "beta_guard_count"));
    read_lm_history(f, "/history", epoch.size(), r.training);
  }
  r.test_loss = f.read_vector("/history/test_loss");
  r.test_predictions = f.read_matrix("/test/predictions");
  r.test_targets = f.read_matrix("/test/targets");
}

RunRecord read_result_in_process(const std::filesystem::path& path) {
  const H5File f = H5File::open_read(path);
  const int version =
      require_format(f, kResultFormat, kResultOldestFormatVersion, kResultFormatVersion);
  if (!is_training_result(f)) {
    RunRecord job = read_job_result(f);
    job.format_version = version;
    job.metrics = current_names(std::move(job.metrics), f, version);
    job.metric_units = current_names(std::move(job.metric_units), f, version);
    return job;
  }
  RunRecord r;
  r.format_version = version;
  r.experiment = f.attribute_string("/", "experiment");
  r.config_hash = f.attribute_string("/", "config_hash");
  r.resolved_yaml = f.read_string("/config");
  r.provenance = read_provenance(f, "/provenance");
  r.dataset_file = f.attribute_string("/dataset", "file");
  r.dataset_hash = f.attribute_string("/dataset", "content_hash");
  r.input_names = f.read_strings("/dataset/input_names");
  r.input_units = f.read_strings("/dataset/input_units");
  r.target_names = f.read_strings("/dataset/target_names");
  r.target_units = f.read_strings("/dataset/target_units");
  r.split.train = f.read_indices("/split/train");
  r.split.validation = f.read_indices("/split/validation");
  r.split.test = f.read_indices("/split/test");

  if (f.has_attribute("/model", "type") && f.attribute_string("/model", "type") == "narx") {
    read_narx_sections(f, r);
  } else {
    read_mlp_sections(f, r);
  }
  r.metrics = current_names(read_metrics(f), f, version);
  if (r.other_inference) {
    r.other_inference->metrics = current_names(std::move(r.other_inference->metrics), f, version);
  }
  r.metric_units = current_names(read_metric_units(f), f, version);
  if (r.metric_units.empty()) r.metric_units = training_metric_units(r);  // older files
  r.warnings = read_warnings(f);
  r.upstream = read_upstream(f);
  return r;
}
}  // namespace

}  // namespace cnclab
