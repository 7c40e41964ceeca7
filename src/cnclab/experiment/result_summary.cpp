#include "cnclab/experiment/result_summary.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/isolated_read.hpp"

namespace cnclab {

namespace {
ResultSummary read_summary_in_process(const std::filesystem::path& path) {
  const H5File f = H5File::open_read(path);
  require_format(f, kResultFormat, kResultFormatVersion);
  ResultSummary s;
  if (f.has_attribute("/", "kind")) s.kind = f.attribute_string("/", "kind");
  s.experiment = f.attribute_string("/", "experiment");
  s.config_hash = f.attribute_string("/", "config_hash");
  s.resolved_yaml = f.read_string("/config");
  s.metrics = read_metrics(f);
  s.metric_units = read_metric_units(f);
  s.warnings = read_warnings(f);
  s.provenance = read_provenance(f, "/provenance");
  if (f.has_attribute("/dataset", "file")) s.dataset_file = f.attribute_string("/dataset", "file");
  for (const auto& u : read_upstream(f)) s.upstream_files.push_back(u.result_file);
  if (f.exists("/outputs/files")) s.output_files = f.read_strings("/outputs/files");
  return s;
}
}  // namespace

ResultSummary read_result_summary(const std::filesystem::path& path) {
  probe_in_child(path, [&] { read_summary_in_process(path); });
  return read_summary_in_process(path);
}

std::vector<SummaryOrError> read_result_summaries(const std::vector<std::filesystem::path>& files) {
  std::vector<SummaryOrError> out(files.size());
  std::vector<ReadOutcome<ResultSummary>> read =
      read_each_isolated<ResultSummary>(files, read_summary_in_process);
  for (std::size_t i = 0; i < files.size(); ++i) {
    try {
      out[i].summary = std::move(read[i]).get();
    } catch (const Error& e) {
      out[i].error = e.what();
    }
  }
  return out;
}

}  // namespace cnclab
