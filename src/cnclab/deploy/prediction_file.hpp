#pragma once
// OUT of `cnclab predict`: the prediction's columns (predict.hpp) with what
// identifies it, written atomically (io/atomic_file.hpp):
//   .h5   root attrs format = "cnclab-prediction", format_version = 1,
//         complete = 1 (last);
//         /provenance  attrs (text): result_file, result_identity,
//                      experiment, config_hash, input, input_kind,
//                      input_hash, split, initial_state, first_step,
//                      samples, cnclab_version, git_commit, created_utc
//         /columns     the column names in order (strings)
//         /predictions/<name>  float64, a value per sample, attr units
//   .csv  "# key: value" lines of the same provenance, then the columns
//         (csv_table.hpp; "name [unit]" headers)
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/deploy/deployed_model.hpp"
#include "cnclab/deploy/predict.hpp"
#include "cnclab/deploy/prediction_input.hpp"

namespace cnclab {

inline constexpr const char* kPredictionFormat = "cnclab-prediction";
inline constexpr int kPredictionFormatVersion = 1;

// ConfigError naming -o unless `out` ends in .h5 or .csv (checked before any work).
void check_prediction_path(const std::filesystem::path& out);

// (key, value) pairs of the provenance above, in order.
std::vector<std::pair<std::string, std::string>> prediction_provenance(
    const DeployedModel& model, const PredictionInput& input, const PredictOptions& options,
    const Prediction& prediction);

// IoError naming `out` when the write fails (nothing is left at `out` then,
// or the file that was there before).
void write_prediction(const std::filesystem::path& out, const DeployedModel& model,
                      const PredictionInput& input, const PredictOptions& options,
                      const Prediction& prediction);

}  // namespace cnclab
