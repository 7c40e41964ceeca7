#pragma once
// A model's values in the layout the exports write them: each weight
// matrix row-major (row i: the weights of unit i), as C arrays and
// torch.nn.Linear hold them (the flat parameter vectors are column-major,
// nn/mlp.hpp and nn/narx.hpp).
#include <cstddef>
#include <vector>

#include "cnclab/deploy/deployed_model.hpp"

namespace cnclab {

// One layer of an mlp: z = W a + b.
struct DenseLayer {
  std::size_t inputs = 0, outputs = 0;
  std::vector<double> weights;  // outputs x inputs, row-major
  std::vector<double> biases;   // outputs
};
std::vector<DenseLayer> mlp_layers(const DeployedModel& model);

// Every network of a narx model (Eq. 1 of seed 002): W1 (H x N) and b1 of the
// hidden layer, W2 (H) and b2 of the output; and the physical columns'
// ranges (ColumnScaling: min and span = max - min), empty without them.
struct NarxWeights {
  std::vector<double> w1;                                  // networks x H x N, row-major
  std::vector<double> b1;                                  // networks x H
  std::vector<double> w2;                                  // networks x H
  std::vector<double> b2;                                  // networks
  std::vector<double> in_min, in_span, out_min, out_span;  // networks
};
NarxWeights narx_weights(const DeployedModel& model);

}  // namespace cnclab
