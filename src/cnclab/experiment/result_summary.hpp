#pragma once
// What listing and reporting many results need of each (cnclab runs, gc,
// report): its header, config, metrics with units and provenance, checked
// like read_result (isolated read, format, version, completeness) without
// reading its arrays.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "cnclab/io/provenance.hpp"

namespace cnclab {

struct ResultSummary {
  std::string kind = "train";  // "train" or the job kind (root attribute `kind`)
  std::string experiment;      // root attribute `experiment`
  std::string config_hash;     // the identity's hash
  std::string resolved_yaml;   // /config
  std::map<std::string, double> metrics;
  std::map<std::string, std::string> metric_units;  // "" or absent: unknown (older files)
  std::vector<std::string> warnings;
  Provenance provenance;  // status and failure_reason inside
  // What it was made from and what it made (gc keeps these with it):
  std::string dataset_file;                 // training runs: /dataset file ("" for jobs)
  std::vector<std::string> upstream_files;  // /upstream result files
  std::vector<std::string> output_files;    // jobs: /outputs files, relative to its folder
};

// Throws IoError naming the file on anything but a complete cnclab result.
ResultSummary read_result_summary(const std::filesystem::path& path);

// Many at once: each file's summary or its error message, with one isolated
// child for a run of readable files (read_each_isolated), so listing
// thousands of files stays fast.
struct SummaryOrError {
  ResultSummary summary;
  std::string error;  // "" when summary is valid
};
std::vector<SummaryOrError> read_result_summaries(const std::vector<std::filesystem::path>& files);

}  // namespace cnclab
