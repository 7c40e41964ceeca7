#pragma once
// A regression dataset: inputs and targets with one sample per column,
// feature names and units, optional per-sample metadata (bookkeeping beside
// the inputs that no model sees, e.g. a tool-path line index), and the
// generator that made it.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace cnclab {

struct Dataset {
  Eigen::MatrixXd inputs;   // n_inputs x n_samples
  Eigen::MatrixXd targets;  // n_outputs x n_samples
  std::vector<std::string> input_names, input_units;
  std::vector<std::string> target_names, target_units;
  // n_metadata x n_samples; zero rows = no metadata (then its column count
  // is ignored).
  Eigen::MatrixXd metadata;
  std::vector<std::string> metadata_names, metadata_units;
  std::string generator;         // e.g. "friedman1"
  std::string generator_config;  // YAML text of the generator's options and seed

  std::size_t num_samples() const { return static_cast<std::size_t>(inputs.cols()); }
  // Sizes consistent (names and units per row, same sample count) and every
  // value finite; throws cnclab::Error naming the matrix, feature and sample.
  void validate() const;
  bool has_metadata() const { return metadata.rows() > 0; }
  // Row index of a metadata column by name, or -1.
  Eigen::Index metadata_row(const std::string& name) const;
  // 16 hex digits of FNV-1a (cnclab::Hasher) over, in order: the shapes of
  // inputs and targets; input names, input units, target names, target
  // units, generator and generator_config (each list and string prefixed by
  // its length, so boundaries count); then the IEEE-754 bytes of inputs and
  // of targets in storage order (sample by sample); then, only when there is
  // metadata (so hashes of datasets without it are unchanged), the metadata
  // shape, names, units and values likewise. Bit-exact: 0.0 and -0.0
  // differ. Identical content gives identical hashes on any platform with
  // little-endian doubles.
  std::string content_hash() const;
};

// The dataset with only the named targets, in the order given (one network
// per output, seed 004 Table 5). Throws ConfigError naming an unknown or
// repeated name and the available ones. Empty `names`: all targets.
Dataset select_targets(const Dataset& dataset, const std::vector<std::string>& names);

}  // namespace cnclab
