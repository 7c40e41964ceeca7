#pragma once
// What `cnclab predict` applies a network to, as named columns:
//   dataset file (.h5)   a cnclab dataset: its inputs, targets and metadata
//   dataset config (.yaml, .yml)  a file with a `dataset:` section (a dataset
//                        config or an experiment), generated on the fly into
//                        the dataset cache (or read from it): a new surface,
//                        face or tool path
//   CSV (.csv)           raw inputs, a column per input (csv_table.hpp)
#include <cstddef>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/data/dataset.hpp"
#include "cnclab/deploy/named_column.hpp"

namespace cnclab {

enum class InputKind { dataset_file, dataset_config, csv };
std::string to_string(InputKind kind);  // "dataset", "dataset config", "csv"

struct PredictionInput {
  InputKind kind = InputKind::csv;
  std::string source;     // the file as given
  std::string hash;       // datasets: their content hash; CSV: FNV-1a of the file's bytes
  std::string generator;  // datasets: their generator; CSV: ""
  std::size_t samples = 0;
  // A dataset's inputs, targets and metadata (units as stored); a CSV's
  // columns (unit "" where its header gives none).
  std::vector<NamedColumn> columns;

  // The column named `name`, or null.
  const NamedColumn* find(const std::string& name) const;
};

struct InputOptions {
  std::vector<std::string> overrides;           // key=value for a dataset config
  std::filesystem::path data_dir = "datasets";  // the dataset cache (configs)
  std::ostream* log = nullptr;                  // generation progress; null: quiet
};

// The columns of dataset `d` (inputs, targets, metadata), its content hash
// and generator.
PredictionInput dataset_input(const Dataset& d, InputKind kind, const std::string& source);

// ConfigError (exit 2) naming the file: an unknown extension, overrides for
// anything but a config, a missing or empty file, a config without a
// `dataset:` section, no samples; the CSV reader's errors. A dataset file
// that is not a readable complete dataset: IoError.
PredictionInput read_prediction_input(const std::filesystem::path& file,
                                      const InputOptions& options);

}  // namespace cnclab
