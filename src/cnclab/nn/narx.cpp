#include "cnclab/nn/narx.hpp"

#include <algorithm>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/kernels.hpp"

namespace cnclab {
namespace {

MlpOptions static_network(const NarxOptions& o) {
  MlpOptions m;
  m.inputs = o.inputs * o.input_delays + o.feedback_delays;
  m.hidden = {o.hidden};
  m.outputs = 1;
  m.hidden_activation = o.hidden_activation;
  m.output_activation = Activation::linear;
  m.weights = o.weights;
  m.biases = o.biases;
  return m;
}

}  // namespace

void NarxOptions::validate() const {
  if (input_delays < 1) {
    throw OptionError("input_delays", std::to_string(input_delays), "must be >= 1");
  }
  if (feedback_delays < 1) {
    throw OptionError("feedback_delays", std::to_string(feedback_delays),
                      "must be >= 1 (a NARX feeds back at least e(t-1))");
  }
  if (hidden < 1) throw OptionError("hidden", std::to_string(hidden), "must be >= 1");
  if (inputs < 1) {
    throw OptionError("inputs", std::to_string(inputs), "must be >= 1 (input channels)");
  }
  if (first_input_delay > 1) {
    throw OptionError("first_input_delay", std::to_string(first_input_delay),
                      "must be 0 (v(t), Eq. 1) or 1 (MATLAB narxnet(1:D, ...))");
  }
  weights.validate();
  biases.validate();
}

Narx::Narx(NarxOptions options)
    : options_((options.validate(), std::move(options))), mlp_(static_network(options_)) {
  kernels::active();  // a CNCLAB_ISA that cannot be honoured fails here, not in step() (noexcept)
}

Eigen::Index Narx::first_step() const {
  const auto last_input = options_.first_input_delay + options_.input_delays - 1;
  return static_cast<Eigen::Index>(std::max(last_input, options_.feedback_delays));
}

void Narx::check_series(const Inputs& v, const Eigen::VectorXd& e) const {
  if (v.cols() != static_cast<Eigen::Index>(options_.inputs)) {
    throw Error("NARX series: " + std::to_string(v.cols()) + " input channel(s), the network has " +
                std::to_string(options_.inputs));
  }
  if (v.rows() != e.size() || v.rows() <= first_step()) {
    throw Error("NARX series: input has " + std::to_string(v.rows()) + " samples, error " +
                std::to_string(e.size()) + "; need equal lengths > " +
                std::to_string(first_step()) + " (the delays)");
  }
  if (!v.allFinite() || !e.allFinite()) throw Error("NARX series contain NaN or infinity");
}

Eigen::MatrixXd Narx::open_loop_regressors(const Inputs& v, const Eigen::VectorXd& e) const {
  check_series(v, e);
  const Eigen::Index t0 = first_step(), steps = v.rows() - t0;
  const auto dv = static_cast<Eigen::Index>(options_.input_delays);
  const auto de = static_cast<Eigen::Index>(options_.feedback_delays);
  const auto d0 = static_cast<Eigen::Index>(options_.first_input_delay);
  const Eigen::Index nv = dv * v.cols();
  Eigen::MatrixXd x(nv + de, steps);
  for (Eigen::Index s = 0; s < steps; ++s) {
    const Eigen::Index t = t0 + s;
    for (Eigen::Index c = 0; c < v.cols(); ++c) {
      for (Eigen::Index j = 0; j < dv; ++j) x(c * dv + j, s) = v(t - d0 - j, c);
    }
    for (Eigen::Index k = 1; k <= de; ++k) x(nv + k - 1, s) = e[t - k];
  }
  return x;
}

Eigen::VectorXd Narx::simulate_closed_loop(const Eigen::VectorXd& params, const Inputs& v,
                                           const Eigen::VectorXd& e_initial,
                                           Eigen::MatrixXd* jacobian) const {
  check_series(v, e_initial);
  const Eigen::Index t0 = first_step(), steps = v.rows() - t0;
  const Eigen::Index channels = v.cols();
  const auto de = static_cast<Eigen::Index>(options_.feedback_delays);
  const auto d0 = static_cast<Eigen::Index>(options_.first_input_delay);
  const auto h = static_cast<Eigen::Index>(options_.hidden);
  // dv: every input-channel regressor (C D_V), fed-back errors after them.
  const auto per_channel = static_cast<Eigen::Index>(options_.input_delays);
  const Eigen::Index dv = per_channel * channels;
  const Eigen::Index n = dv + de, w_count = params.size();
  if (w_count != static_cast<Eigen::Index>(num_parameters())) {
    throw Error("NARX parameters: " + std::to_string(w_count) + " values, the network has " +
                std::to_string(num_parameters()));
  }
  const Eigen::Map<const Eigen::VectorXd> w2(params.data() + h * n + h, h);

  // e_full(t): initial states then predictions.
  Eigen::VectorXd e_full(v.rows());
  e_full.head(t0) = e_initial.head(t0);
  Eigen::VectorXd x(n), a(h), delta(h);  // delta_i = w2_i f'(z_i)
  // The predictions step through Narx::step (as the real-time predictor).
  // The RTRL rows are computed kBlock steps at a time by the kernel
  // (nn/kernels.hpp, rtrl_block: its formula) from each step's regressor,
  // hidden activations and delta, in a row-major scratch (each step's row
  // contiguous, the recursion reads the de rows before it) and copied to
  // the column-major Jacobian a block at a time: writing and re-reading rows
  // of a (steps x W) column-major matrix directly strides by `steps` doubles
  // per entry: 1.4x the CPU time at 87,000 steps (12 neurons, 4/4).
  constexpr Eigen::Index kBlock = 64;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor sens;  // rows [0, de): the de rows before the block; [de, de + kBlock): the block
  Eigen::MatrixXd block_x, block_a, block_delta;  // one column per step of the block
  const kernels::Table& kernel = kernels::active();
  if (jacobian != nullptr) {
    jacobian->resize(steps, w_count);
    sens.setZero(de + kBlock, w_count);  // S = 0 on the initial states
    block_x.resize(n, kBlock);
    block_a.resize(h, kBlock);
    block_delta.resize(h, kBlock);
  }
  for (Eigen::Index s = 0; s < steps; ++s) {
    const Eigen::Index t = t0 + s;
    for (Eigen::Index c = 0; c < channels; ++c) {
      for (Eigen::Index j = 0; j < per_channel; ++j) x[c * per_channel + j] = v(t - d0 - j, c);
    }
    for (Eigen::Index k = 1; k <= de; ++k) x[dv + k - 1] = e_full[t - k];
    e_full[t] = step(params, x, a);
    if (jacobian == nullptr) continue;
    delta = w2;
    multiply_derivative(options_.hidden_activation, a, delta);
    const Eigen::Index c = s % kBlock;
    block_x.col(c) = x;
    block_a.col(c) = a;
    block_delta.col(c) = delta;
    if (c != kBlock - 1 && s != steps - 1) continue;
    kernels::RtrlBlock b;
    b.rows = c + 1;
    b.hidden = h;
    b.input_delays = dv;
    b.feedback_delays = de;
    b.w1 = params.data();
    b.x = block_x.data();
    b.a = block_a.data();
    b.delta = block_delta.data();
    b.sens = sens.data();
    b.jacobian = jacobian->data() + (s + 1 - b.rows);
    b.ld_jacobian = jacobian->outerStride();
    kernel.rtrl_block(b);
  }
  return e_full.tail(steps);
}

double Narx::step(const Eigen::VectorXd& params, const Eigen::VectorXd& x,
                  Eigen::VectorXd& hidden) const noexcept {
  const auto h = static_cast<Eigen::Index>(options_.hidden);
  const Eigen::Index n = x.size();
  const Eigen::Map<const Eigen::MatrixXd> w1(params.data(), h, n);
  const Eigen::Map<const Eigen::VectorXd> b1(params.data() + h * n, h);
  const Eigen::Map<const Eigen::VectorXd> w2(params.data() + h * n + h, h);
  hidden.noalias() = w1 * x;
  hidden += b1;
  apply_activation(options_.hidden_activation, hidden);
  return w2.dot(hidden) + params[h * n + 2 * h];
}

}  // namespace cnclab
