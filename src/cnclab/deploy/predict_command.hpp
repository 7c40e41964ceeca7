#pragma once
// `cnclab predict RESULT.h5 INPUT -o OUT.h5|.csv`: the whole command as the
// library does it (the CLI parses, calls and prints).
#include <filesystem>
#include <string>
#include <vector>

#include "cnclab/deploy/deployed_model.hpp"
#include "cnclab/deploy/predict.hpp"

namespace cnclab {

struct PredictRequest {
  std::filesystem::path result;        // RESULT.h5
  std::filesystem::path input;         // a dataset, a dataset config or a CSV
  std::filesystem::path out;           // OUT.h5 or OUT.csv
  std::vector<std::string> overrides;  // key=value for a dataset config
  PredictOptions options;
  TrainingDataOptions data;  // dataset cache (configs; a narx model's training data)
};

// Checks, predicts and writes OUT (atomically; nothing on bad input);
// returns the lines to print: what was written, the notes, and per
// predicted column with a measured one its RMS and largest difference.
std::vector<std::string> run_predict(const PredictRequest& request);

}  // namespace cnclab
