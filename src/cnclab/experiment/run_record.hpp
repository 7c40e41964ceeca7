#pragma once
// Everything one run produced, in memory: what result_file.cpp writes and
// reads back. Plain data.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

#include "cnclab/data/split.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/train/sgdm.hpp"

namespace cnclab {

// Per-feature normaliser parameters: z-score (mean, std) or min-max (min,
// max and the range [low, high]); all empty when the scaling is `none`.
struct ScalingRecord {
  Eigen::VectorXd mean;
  Eigen::VectorXd std;
  Eigen::VectorXd min, max;
  double low = -1.0, high = 1.0;
  std::string method() const { return mean.size() ? "zscore" : min.size() ? "minmax" : "none"; }
};

struct RunRecord {
  std::string experiment;     // spec.name
  std::string resolved_yaml;  // the full resolved config
  std::string config_hash;    // identity of the run: hash of resolved_yaml
  Provenance provenance;
  std::string dataset_file;  // path of the cached dataset used
  std::string dataset_hash;  // its content hash
  std::vector<std::string> input_names, input_units, target_names, target_units;

  Split split;
  MlpOptions model;  // inputs/outputs filled in
  Eigen::VectorXd parameters;
  ScalingRecord input_scaling, target_scaling;

  Summary training;
  std::vector<double> test_loss;  // per epoch, MSE in normalised units (NaN if no test set)

  Eigen::MatrixXd test_predictions;  // physical units, one sample per column
  Eigen::MatrixXd test_targets;
  std::map<std::string, double> metrics;
};

}  // namespace cnclab
