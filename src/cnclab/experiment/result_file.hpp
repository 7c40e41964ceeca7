#pragma once
// The HDF5 result file of one run (layout: README.md, "Where results go").
//
// Written under a partial name and renamed when complete; the root attribute
// `complete` = 1 is the last thing written, so a file without it (or with a
// partial name) is never taken for a result.
#include <filesystem>
#include <map>
#include <ostream>
#include <string>

#include "cnclab/experiment/run_record.hpp"

namespace cnclab {

inline constexpr const char* kResultFormat = "cnclab-result";
inline constexpr int kResultFormatVersion = 1;

void write_result(const std::filesystem::path& path, const RunRecord& record);

// Reads and checks a result file: format, version, completeness, shapes.
// Throws IoError naming the file and the object on anything else.
RunRecord read_result(const std::filesystem::path& path);

// What sweeps need of each trial: a result's status and metrics, checked
// like read_result (safe read, format, version, completeness) but without
// reading its arrays (several times faster).
struct ResultStatus {
  std::string status;          // "complete" | "failed"
  std::string failure_reason;  // failed only
  std::map<std::string, double> metrics;
  std::vector<UpstreamRef> upstream;  // the upstream results it was made from
};
ResultStatus read_result_status(const std::filesystem::path& path);

// The parts every result has, shared with job results (job_result.hpp):
// root attributes format, kind (jobs only), experiment, config_hash, status,
// then /config and /provenance (write_result_header); /metrics (one
// attribute each, plus `units`); /upstream; and `show`'s config block.
class H5File;
void write_result_header(H5File& file, const RunRecord& record);
void print_result_config(const std::string& resolved_yaml, std::ostream& out);
void write_result_upstream(H5File& file, const std::vector<UpstreamRef>& upstream);
std::map<std::string, double> read_metrics(const H5File& file);
std::vector<UpstreamRef> read_upstream(const H5File& file);

// Human-readable summary for `cnclab show` (job results: print_job_result).
void print_result(const RunRecord& record, std::ostream& out);

}  // namespace cnclab
