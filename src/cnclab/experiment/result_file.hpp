#pragma once
// The HDF5 result file of one run (layout: README.md, "Where results go";
// declared once in result_layout.hpp). Written by result_writer.cpp, read by
// result_reader.cpp, printed for `show` by result_print.cpp.
//
// Written under a partial name and renamed when complete; the root attribute
// `complete` = 1 is the last thing written, so a file without it (or with a
// partial name) is never taken for a result.
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/io/isolated_read.hpp"

namespace cnclab {

inline constexpr const char* kResultFormat = "cnclab-result";
// 2: training metrics per split ("test.rmse", nn/metrics.hpp). 1: the mlp's
// metrics of the test split as "rmse" ..., normalised_mse (test) and
// normalised_validation_mse, a narx run's of its validation half under their
// registered names; read with format1_metric_name (job results: the
// training metrics among theirs, a sweep job's selected trial's).
inline constexpr int kResultFormatVersion = 2;
inline constexpr int kResultOldestFormatVersion = 1;

// Today's name of a training metric stored by result format 1 (and sweep
// plans and summaries of then): normalised_validation_mse is
// validation.normalised_mse; the mlp's metrics (base_metrics(), nn/metrics.hpp)
// were of the test split: "rmse" is test.rmse; every other name was a
// sequence metric of a narx run's validation half: validation.<name>. A name
// with a split stays.
std::string format1_metric_name(const std::string& name);

void write_result(const std::filesystem::path& path, const RunRecord& record);

// Reads and checks a result file: format, version, completeness, shapes.
// Throws IoError naming the file and the object on anything else.
RunRecord read_result(const std::filesystem::path& path);
// Many files: read_result's value or exception per file, with one isolated
// child for a run of readable files (io/isolated_read.hpp).
std::vector<ReadOutcome<RunRecord>> read_results(const std::vector<std::filesystem::path>& paths);

// What sweeps need of each trial: a result's status and metrics, checked
// like read_result (safe read, format, version, completeness) but without
// reading its arrays (several times faster).
struct ResultStatus {
  std::string status;                               // "complete" | "failed"
  std::string failure_reason;                       // failed only
  std::map<std::string, double> metrics;            // today's names (format1_metric_name)
  std::map<std::string, std::string> metric_units;  // per metric; empty in the oldest files
  std::vector<std::string> warnings;                // complete only (run_warnings.hpp)
  std::vector<UpstreamRef> upstream;                // the upstream results it was made from
};
ResultStatus read_result_status(const std::filesystem::path& path);
// Many files, as read_results.
std::vector<ReadOutcome<ResultStatus>> read_result_statuses(
    const std::vector<std::filesystem::path>& paths);

// The parts every result has, shared with job results (job_result.hpp):
// root attributes format, kind (jobs only), experiment, config_hash, status,
// warnings (when any), then /config and /provenance (write_result_header);
// /metrics (one number attribute per metric, nothing else) and /metrics/units
// (one text attribute per metric, its unit); /upstream; and `show`'s config
// block.
class H5File;
void write_result_header(H5File& file, const RunRecord& record);
void write_metrics(H5File& file, const std::map<std::string, double>& metrics,
                   const std::map<std::string, std::string>& units);
// /metrics/units; empty for files written before it existed.
std::map<std::string, std::string> read_metric_units(const H5File& file);
// The units of a training record's metrics: mlp, metric_unit (nn/metrics.hpp)
// over its target units; narx, the units its study registered
// (sequence_metrics.hpp).
std::map<std::string, std::string> training_metric_units(const RunRecord& record);
// What `cnclab show` prints of a result.
struct ShowOptions {
  bool full_config = false;  // every array of the config (else abbreviate_config)
};
// The "config" block: the resolved YAML indented, large arrays abbreviated
// unless options.full_config (core/config_abbreviate.hpp).
void print_result_config(const std::string& resolved_yaml, std::ostream& out,
                         const ShowOptions& options = {});
// "metrics      (note)" then one line per metric: name, value, unit
// (record.metric_units; "1" shown as "1 (dimensionless)").
void print_metrics(const RunRecord& record, const std::string& note, std::ostream& out);
void write_result_upstream(H5File& file, const std::vector<UpstreamRef>& upstream);
// Every /metrics attribute but a `units` text (files before /metrics/units).
std::map<std::string, double> read_metrics(const H5File& file);
std::vector<UpstreamRef> read_upstream(const H5File& file);
std::vector<std::string> read_warnings(const H5File& file);  // none when absent (older files)

// How a training run used its validation part, for people (`run` and `show`
// print it): a trainer without a validation stop (its capabilities,
// train/trainer_registry.hpp; Bayesian regularisation, as in MATLAB) holds
// its validation split out of training and only scores it; a narx run's
// stages never stop on the validation half. Empty for the other trainers
// (their validation stop, when configured, is in the training message).
std::vector<std::string> validation_notes(const RunRecord& record);

// provenance_lines (io/provenance.hpp) as `show` lines: label padded to 13.
void print_provenance(const Provenance& provenance, std::ostream& out);

// Human-readable summary for `cnclab show` (job results: print_job_result).
void print_result(const RunRecord& record, std::ostream& out, const ShowOptions& options = {});

}  // namespace cnclab
