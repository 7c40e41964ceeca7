#pragma once
// Dataset files (HDF5), layout:
//   /            attrs format="cnclab-dataset", format_version=1, generator,
//                content_hash, complete=1 (written last)
//   /inputs      (N, n_inputs)  float64, attr units (per-feature units in /input_units)
//   /targets     (N, n_outputs) float64
//   /input_names, /input_units, /target_names, /target_units   string lists
//   /generator_config   YAML text
#include <filesystem>

#include "cnclab/data/dataset.hpp"

namespace cnclab {

inline constexpr const char* kDatasetFormat = "cnclab-dataset";
inline constexpr int kDatasetFormatVersion = 1;

// Validates, then writes atomically (temporary name + rename).
void write_dataset(const std::filesystem::path& path, const Dataset& dataset);
// Reads and verifies format, version, completeness, shapes and content hash;
// IoError naming the file otherwise.
Dataset read_dataset(const std::filesystem::path& path);

}  // namespace cnclab
