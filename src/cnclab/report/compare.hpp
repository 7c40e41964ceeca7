#pragma once
// `cnclab compare`: runs side by side. Inputs are result files, run folders
// (every result file below them) or sweep folders (their trials); the output
// lists only the config keys whose values differ between runs (a key one run
// lacks shows as "—"), then every metric with its delta to the first run.
#include <filesystem>
#include <map>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/run_record.hpp"

namespace cnclab {

enum class CompareFormat { table, markdown, csv, json };
// "table", "md", "csv", "json"; ConfigError otherwise.
CompareFormat parse_compare_format(const std::string& text);

struct ComparedRun {
  std::filesystem::path file;
  RunRecord record;
};

// Result files named by `inputs` (files as given; a sweep folder: its trials
// in plan order; other folders: every *.h5 below them except partial
// temporaries and summary.h5, sorted). IoError on an
// unreadable file; ConfigError on a missing path or fewer than two runs.
std::vector<ComparedRun> collect_runs(const std::vector<std::string>& inputs);

// The resolved config flattened to dotted keys, leaf values as YAML text
// (lists in flow style), in document order: ("model.hidden", "[64, 32]"), ...
// Without `full`, an array of more than kAbbreviateScalars numbers is its
// shape and hash, as `show` prints it (core/config_abbreviate.hpp:
// "16 × 16 × 3, hash 1a2b3c4d"; equal arrays, equal text).
std::vector<std::pair<std::string, std::string>> flatten_config(const std::string& yaml_text,
                                                                bool full = true);

// `full`: arrays in full (else abbreviated, in every format).
void print_comparison(const std::vector<ComparedRun>& runs, CompareFormat format, std::ostream& out,
                      bool full = false);

int compare_command(const std::vector<std::string>& inputs, const std::string& format, bool full,
                    std::ostream& out);

}  // namespace cnclab
