// Reading result files (declared in result_file.hpp; layout: result_layout.hpp),
// older formats under today's metric names.
#include <algorithm>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_layout.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/isolated_read.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {

std::string format1_metric_name(const std::string& name) {
  if (name == kOlderValidationMse) return metric_name("validation", "normalised_mse");
  if (!metric_split(name).empty()) return name;
  const auto& mlp = base_metrics();
  const bool of_test = std::find(mlp.begin(), mlp.end(), name) != mlp.end();
  return metric_name(of_test ? "test" : "validation", name);
}

std::map<std::string, double> read_metrics(const H5File& f) {
  std::map<std::string, double> metrics;
  std::map<std::string, std::string> units;
  ResultLayoutReader io(f);
  result_layout::metrics(io, metrics, units);
  return metrics;
}

std::map<std::string, std::string> read_metric_units(const H5File& f) {
  std::map<std::string, double> metrics;
  std::map<std::string, std::string> units;
  ResultLayoutReader io(f);
  result_layout::metrics(io, metrics, units);
  return units;
}

std::vector<std::string> read_warnings(const H5File& f) {
  if (!f.has_attribute("/", "warnings")) return {};
  return split_warnings(f.attribute_string("/", "warnings"));
}

std::vector<UpstreamRef> read_upstream(const H5File& f) {
  std::vector<UpstreamRef> refs;
  ResultLayoutReader io(f);
  result_layout::upstream(io, refs);
  return refs;
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
  ResultLayoutReader io(f);
  result_layout::header(io, r);
  result_layout::training(io, r);
  result_layout::metrics(io, r.metrics, r.metric_units);
  r.metrics = current_names(std::move(r.metrics), f, version);
  if (r.other_inference) {
    r.other_inference->metrics = current_names(std::move(r.other_inference->metrics), f, version);
  }
  r.metric_units = current_names(std::move(r.metric_units), f, version);
  if (r.metric_units.empty()) r.metric_units = training_metric_units(r);  // older files
  r.warnings = read_warnings(f);
  result_layout::upstream(io, r.upstream);
  return r;
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

std::vector<ReadOutcome<RunRecord>> read_results(const std::vector<std::filesystem::path>& paths) {
  return read_each_isolated<RunRecord>(paths, read_result_in_process);
}

std::vector<ReadOutcome<ResultStatus>> read_result_statuses(
    const std::vector<std::filesystem::path>& paths) {
  return read_each_isolated<ResultStatus>(paths, read_status_in_process);
}

}  // namespace cnclab
