#include "cnclab/deploy/export_weights.hpp"

namespace cnclab {

std::vector<DenseLayer> mlp_layers(const DeployedModel& m) {
  const Mlp mlp(m.mlp);
  const auto& sizes = mlp.layer_sizes();
  std::vector<DenseLayer> layers;
  Eigen::Index offset = 0;  // W_l (column-major) then b_l, layer by layer
  for (std::size_t l = 1; l < sizes.size(); ++l) {
    const Eigen::Index in = sizes[l - 1], out = sizes[l];
    DenseLayer layer{static_cast<std::size_t>(in), static_cast<std::size_t>(out), {}, {}};
    for (Eigen::Index i = 0; i < out; ++i) {
      for (Eigen::Index j = 0; j < in; ++j)
        layer.weights.push_back(m.parameters[offset + j * out + i]);
    }
    for (Eigen::Index i = 0; i < out; ++i)
      layer.biases.push_back(m.parameters[offset + in * out + i]);
    layers.push_back(std::move(layer));
    offset += (in + 1) * out;
  }
  return layers;
}

NarxWeights narx_weights(const DeployedModel& m) {
  NarxWeights w;
  const auto h = static_cast<Eigen::Index>(m.narx.hidden);
  const auto n = static_cast<Eigen::Index>(m.narx.input_delays + m.narx.feedback_delays);
  for (const NarxNetwork& net : m.networks) {
    const Eigen::VectorXd& q = net.parameters;  // W1 (h x n, column-major), b1, W2, b2
    for (Eigen::Index i = 0; i < h; ++i) {
      for (Eigen::Index j = 0; j < n; ++j) w.w1.push_back(q[j * h + i]);
    }
    for (Eigen::Index i = 0; i < h; ++i) w.b1.push_back(q[h * n + i]);
    for (Eigen::Index i = 0; i < h; ++i) w.w2.push_back(q[h * n + h + i]);
    w.b2.push_back(q[h * n + 2 * h]);
  }
  for (std::size_t a = 0; a < m.physical_inputs.size(); ++a) {
    w.in_min.push_back(m.physical_inputs[a].min);
    w.in_span.push_back(m.physical_inputs[a].max - m.physical_inputs[a].min);
    w.out_min.push_back(m.physical_targets[a].min);
    w.out_span.push_back(m.physical_targets[a].max - m.physical_targets[a].min);
  }
  return w;
}

}  // namespace cnclab
