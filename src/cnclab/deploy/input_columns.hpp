#pragma once
// The columns a model reads, found in an input by name and checked: every
// input column present (each in the model's unit where the input names
// one), targets all or none, a dataset of the model's generator, no CSV
// column the model does not know. A narx model with physical columns reads
// the physical ones when the input has them (a dataset of another tool path
// stores its own scaling; the physical values mapped with the training
// ranges are what the network knows), else the dataset's.
#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "cnclab/deploy/deployed_model.hpp"
#include "cnclab/deploy/prediction_input.hpp"

namespace cnclab {

struct ModelColumns {
  std::vector<std::size_t> samples;  // the input's samples used, in order
  // model.num_inputs() x samples, in the dataset's units (the network's for
  // narx; physical columns mapped with ColumnScaling::to_dataset).
  Eigen::MatrixXd inputs;
  // model.num_outputs() x samples likewise; 0 rows when the input has none.
  Eigen::MatrixXd targets;
  // The extension's context columns the input has, over `samples`.
  std::map<std::string, Eigen::VectorXd> context;
  std::vector<std::string> notes;  // which columns were read
  bool has_targets() const { return targets.rows() > 0; }
};

// `split` as PredictOptions::split. ConfigError (exit 2) naming INPUT and
// the reason (see the header comment).
ModelColumns model_columns(const DeployedModel& model, const PredictionInput& input,
                           const std::string& split);

}  // namespace cnclab
