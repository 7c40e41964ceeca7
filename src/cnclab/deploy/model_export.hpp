#pragma once
// `cnclab export RESULT.h5 --format c|torch -o DIR`: the files of one export
// (c_export.hpp: NAME.h and NAME.c; torch_export.hpp: NAME.py), each written
// atomically into DIR, after every check passed (nothing is written on bad
// input).
#include <filesystem>
#include <string>
#include <vector>

#include "cnclab/deploy/code_text.hpp"
#include "cnclab/deploy/deployed_model.hpp"

namespace cnclab {

struct ExportOptions {
  std::string format = "c";             // c | torch
  std::filesystem::path out_dir = ".";  // DIR, created when absent
  std::string name;                     // NAME; empty: export_identifier(experiment)
  std::string precision = "double";     // c: double | float; torch: double only
  TrainingDataOptions data;             // the training dataset (narx ranges, float bound)
};

struct ExportReport {
  std::vector<std::filesystem::path> files;  // written
  std::vector<std::string> lines;            // for the user: what was written, the float bound
};

// ConfigError (exit 2) for an unknown format or precision, a bad name, a
// result that is not a trained network (deployed_model.hpp).
ExportReport export_model(const std::filesystem::path& result_file, const ExportOptions& options);

// The float export's stated bound (float_bound.hpp) over the model's own
// data: an mlp's test split (else its validation, else its training part),
// a narx model's validation half from standstill; the maximum per output,
// as header lines.
std::vector<std::string> float_bound_statement(const DeployedModel& model,
                                               const TrainingDataOptions& data);

}  // namespace cnclab
