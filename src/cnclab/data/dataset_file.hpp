#pragma once
// Dataset files (HDF5). Layout (N samples, d inputs, m outputs):
//   /                  attrs format = "cnclab-dataset", format_version = 2 (int64),
//                      generator, content_hash (Dataset::content_hash, 16 hex),
//                      complete = 1 (int64, written last)
//   /inputs            (N, d) float64, attr units: the common unit of the
//                      inputs, or "mixed: see /input_units"
//   /targets           (N, m) float64, attr units likewise
//   /input_names       (d) strings    /input_units   (d) strings
//   /target_names      (m) strings    /target_units  (m) strings
//   /generator_config  scalar string: YAML text of the generator options
//   /metadata          (N, k) float64, only when the dataset has metadata
//                      (version 2), attr units likewise
//   /metadata_names    (k) strings    /metadata_units (k) strings
// Version 1 files (no metadata) are still read.
// Strings are fixed-length UTF-8. Row i of /inputs is sample i (h5py:
// f["inputs"][i]).
#include <filesystem>

#include "cnclab/data/dataset.hpp"

namespace cnclab {

inline constexpr const char* kDatasetFormat = "cnclab-dataset";
inline constexpr int kDatasetFormatVersion = 2;
// The oldest format_version read_dataset still reads (1: no metadata).
inline constexpr int kDatasetOldestFormatVersion = 1;

// Validates, then writes atomically (temporary name + rename).
void write_dataset(const std::filesystem::path& path, const Dataset& dataset);
// Reads and verifies format, version, completeness, shapes and content hash;
// IoError naming the file otherwise.
Dataset read_dataset(const std::filesystem::path& path);

}  // namespace cnclab
