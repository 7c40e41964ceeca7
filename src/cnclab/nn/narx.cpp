#include "cnclab/nn/narx.hpp"

#include <algorithm>
#include <string>

#include "cnclab/core/error.hpp"

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
    : options_((options.validate(), std::move(options))), mlp_(static_network(options_)) {}

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
  const Eigen::Map<const Eigen::MatrixXd> w1(params.data(), h, n);  // Mlp layout
  const Eigen::Map<const Eigen::VectorXd> w2(params.data() + h * n + h, h);

  // e_full(t): initial states then predictions.
  Eigen::VectorXd e_full(v.rows());
  e_full.head(t0) = e_initial.head(t0);
  Eigen::VectorXd x(n), a(h), delta(h);  // delta_i = w2_i f'(z_i)
  // RTRL rows are built in a row-major scratch (each step's row contiguous,
  // the recursion reads the de rows before it) and copied to the
  // column-major Jacobian kBlock rows at a time: writing and re-reading
  // rows of a (steps x W) column-major matrix directly strides by `steps`
  // doubles per entry: 1.4x the CPU time at 87,000 steps (12 neurons, 4/4).
  constexpr Eigen::Index kBlock = 64;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  RowMajor sens;  // rows [0, de): the de rows before the block; [de, de + kBlock): the block
  if (jacobian != nullptr) {
    jacobian->resize(steps, w_count);
    sens.setZero(de + kBlock, w_count);
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
    const Eigen::Index r = de + s % kBlock;
    auto row = sens.row(r);
    // Direct term df/dw at x(t).
    for (Eigen::Index j = 0; j < n; ++j) row.segment(j * h, h) = delta.transpose() * x[j];
    row.segment(h * n, h) = delta.transpose();
    row.segment(h * n + h, h) = a.transpose();
    row[h * n + 2 * h] = 1.0;
    // Through the fed-back predictions: df/de(t-k) = sum_i delta_i W1(i, dv+k-1);
    // S = 0 on the initial states (the zero rows before the first block).
    for (Eigen::Index k = 1; k <= de; ++k) row += delta.dot(w1.col(dv + k - 1)) * sens.row(r - k);
    const bool block_full = s % kBlock == kBlock - 1 || s == steps - 1;
    if (!block_full) continue;
    const Eigen::Index rows = s % kBlock + 1;
    jacobian->middleRows(s + 1 - rows, rows) = sens.middleRows(de, rows);
    sens.topRows(de) = sens.middleRows(rows, de).eval();  // the last de rows
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
