#pragma once
// A regression dataset: inputs and targets with one sample per column,
// feature names and units, and the generator that made it.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace cnclab {

struct Dataset {
  Eigen::MatrixXd inputs;   // n_inputs x n_samples
  Eigen::MatrixXd targets;  // n_outputs x n_samples
  std::vector<std::string> input_names, input_units;
  std::vector<std::string> target_names, target_units;
  std::string generator;         // e.g. "friedman1"
  std::string generator_config;  // YAML text of the generator's options and seed

  std::size_t num_samples() const { return static_cast<std::size_t>(inputs.cols()); }
  // Sizes consistent (names and units per row, same sample count) and every
  // value finite; throws cnclab::Error naming the matrix, feature and sample.
  void validate() const;
  // FNV-1a over shapes, names, units, generator, generator config and values.
  std::string content_hash() const;
};

}  // namespace cnclab
