#pragma once
// The result file of a `kind: <job>` file (Table 8 timing, G-code, sweep
// selection): the standard result format (result_file.hpp: root `format`,
// `complete` written last, atomic) with the parts every result has and no
// training parts. `cnclab show`, `cnclab compare`, read_result_status and the
// result store read it like any result.
//
// Layout: root attributes format, format_version, kind (the job kind),
// experiment (the job's name), config_hash, status, complete; /config (the
// job's resolved configuration); /provenance; /metrics (one attribute each);
// /upstream (results it read, as in training results); /outputs (roles and
// files beside the result, relative to its folder); /job (one text attribute
// per fact).
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/result_store.hpp"
#include "cnclab/experiment/run_record.hpp"

namespace cnclab {

class H5File;
struct ShowOptions;

// How a job was asked for: the command's `key=value` overrides and its
// --profile, as its loader was given them (provenance, not identity: the
// resolved config already holds their effect).
struct JobRequest {
  std::vector<std::string> overrides;
  std::string profile;
};

// A job record: kind, name, resolved config and its hash, provenance
// (version, host, start time, the request's overrides and profile; status
// complete) filled in.
RunRecord make_job_record(const std::string& kind, const ResultKey& key, const JobRequest& request);

// Writes atomically; std::logic_error for record.kind "train".
void write_job_result(const std::filesystem::path& path, const RunRecord& record);

// Reads the job parts of an open result file whose root `kind` is not train
// (result_file.cpp dispatches here).
RunRecord read_job_result(const H5File& file);

// `cnclab show` of a job result.
void print_job_result(const RunRecord& record, std::ostream& out, const ShowOptions& options);

// The output with this role, as a path beside `result_file`; IoError naming
// the role when the record has none.
std::filesystem::path output_path(const RunRecord& record, const std::filesystem::path& result_file,
                                  const std::string& role);

}  // namespace cnclab
