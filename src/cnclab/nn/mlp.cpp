#include "cnclab/nn/mlp.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/kernels.hpp"
#include "cnclab/nn/mlp_fields.hpp"

namespace cnclab {
namespace {

using MapMatrix = Eigen::Map<const Eigen::MatrixXd>;
using MapVector = Eigen::Map<const Eigen::VectorXd>;
template <class T>
using Matrix = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
template <class T>
using Vector = Eigen::Matrix<T, Eigen::Dynamic, 1>;

}  // namespace

std::string to_string(DropoutPlacement p) {
  return p == DropoutPlacement::between_hidden ? "between_hidden" : "after_every_hidden";
}

std::string to_string(DropoutInference i) {
  return i == DropoutInference::deterministic ? "deterministic" : "mc";
}

void MlpOptions::validate() const {
  if (inputs < 1) throw OptionError("inputs", std::to_string(inputs), "must be at least 1");
  if (outputs < 1) throw OptionError("outputs", std::to_string(outputs), "must be at least 1");
  // The declared rules (hidden widths, dropout, the initialisers' fields),
  // errors naming the YAML key (dropout.keep_probability); then each
  // initialiser's cross-field rule.
  mlp_option_fields().check(*this);
  weights.validate();
  biases.validate();
}

Mlp::Mlp(MlpOptions options) : options_(std::move(options)) {
  options_.validate();
  sizes_.push_back(static_cast<Eigen::Index>(options_.inputs));
  for (auto h : options_.hidden) sizes_.push_back(static_cast<Eigen::Index>(h));
  sizes_.push_back(static_cast<Eigen::Index>(options_.outputs));
  const std::size_t L = num_layers();
  Eigen::Index offset = 0;
  for (std::size_t l = 1; l <= L; ++l) {
    offsets_.push_back(offset);
    offset += (sizes_[l - 1] + 1) * sizes_[l];
  }
  num_parameters_ = static_cast<std::size_t>(offset);
  dropout_.assign(L + 1, false);
  if (options_.dropout_keep_probability < 1.0) {
    // Hidden layers are l = 1..L-1.
    const std::size_t last =
        options_.dropout_placement == DropoutPlacement::between_hidden ? L - 1 : L;
    for (std::size_t l = 1; l < last; ++l) dropout_[l] = true;
  }
}

void Mlp::initialise(Eigen::VectorXd& params, Rng& rng) const {
  params.resize(static_cast<Eigen::Index>(num_parameters_));
  for (std::size_t l = 1; l <= num_layers(); ++l) {
    const Eigen::Index in = sizes_[l - 1], out = sizes_[l];
    Eigen::Map<Eigen::MatrixXd> w(params.data() + weight_offset(l - 1), out, in);
    Eigen::Map<Eigen::MatrixXd> b(params.data() + weight_offset(l - 1) + in * out, out, 1);
    options_.weights.fill(w, in, out, rng);
    options_.biases.fill(b, in, out, rng);
  }
}

Eigen::MatrixXd Mlp::predict(const Eigen::VectorXd& params, const Eigen::MatrixXd& x) const {
  if (x.rows() != sizes_.front()) {
    throw Error("Mlp::predict: expected " + std::to_string(sizes_.front()) + " input rows, got " +
                std::to_string(x.rows()));
  }
  Eigen::MatrixXd a = x;
  for (std::size_t l = 1; l <= num_layers(); ++l) {
    const Eigen::Index in = sizes_[l - 1], out = sizes_[l];
    const MapMatrix w(params.data() + weight_offset(l - 1), out, in);
    const MapVector b(params.data() + weight_offset(l - 1) + in * out, out);
    Eigen::MatrixXd z(out, a.cols());
    kernels::multiply(kernels::active(), w, false, a, false, z);
    z.colwise() += b;
    apply_activation(activation(l), z);
    a = std::move(z);
  }
  return a;
}

template <class T>
void Mlp::prepare_impl(MlpWorkspace<T>& ws, Eigen::Index batch) const {
  if (ws.batch == batch && ws.a.size() == sizes_.size()) return;
  const std::size_t n = sizes_.size();
  ws.a.resize(n);
  ws.d.resize(n);
  ws.mask.resize(n);
  ws.delta.resize(n);
  for (std::size_t l = 0; l < n; ++l) {
    ws.a[l].resize(sizes_[l], batch);
    ws.delta[l].resize(sizes_[l], batch);
    if (dropout_[l]) {
      ws.d[l].resize(sizes_[l], batch);
      ws.mask[l].resize(sizes_[l], batch);
    }
  }
  ws.batch = batch;
}

void Mlp::prepare(Workspace& ws, Eigen::Index batch) const {
  prepare_impl(ws, batch);
}

void Mlp::prepare(Workspace32& ws, Eigen::Index batch) const {
  prepare_impl(ws, batch);
}

template <class T>
void Mlp::draw_masks_impl(MlpWorkspace<T>& ws, Rng& rng) const {
  const double p = options_.dropout_keep_probability;
  const T scale = static_cast<T>(1.0 / p);
  // r = 1 iff u < p with u = k 2^-53 (Rng::uniform, k the top 53 bits of the
  // next 64-bit draw). k 2^-53 and p 2^53 are exact, so u < p iff
  // k < p 2^53 iff k < ceil(p 2^53): the same masks as comparing uniform()
  // with p, without the unpredictable branch per unit: k, threshold <= 2^53,
  // so k - threshold wraps to a set top bit iff k < threshold.
  const auto threshold = static_cast<std::uint64_t>(std::ceil(std::ldexp(p, 53)));
  for (std::size_t l = 0; l < sizes_.size(); ++l) {
    if (!dropout_[l]) continue;
    T* const m = ws.mask[l].data();
    const Eigen::Index size = ws.mask[l].size();
    for (Eigen::Index i = 0; i < size; ++i) {
      const std::uint64_t keep = ((rng.next_u64() >> 11) - threshold) >> 63;
      m[i] = static_cast<T>(keep) * scale;
    }
  }
}

void Mlp::draw_dropout_masks(Workspace& ws, Rng& rng) const {
  draw_masks_impl(ws, rng);
}

void Mlp::draw_dropout_masks(Workspace32& ws, Rng& rng) const {
  draw_masks_impl(ws, rng);
}

template <class T>
T Mlp::loss_and_gradient_impl(const Vector<T>& params, const Eigen::Ref<const Matrix<T>>& x,
                              const Eigen::Ref<const Matrix<T>>& y, MlpWorkspace<T>& ws,
                              Vector<T>& gradient) const {
  using ConstMap = Eigen::Map<const Matrix<T>>;
  const kernels::Table& k = kernels::active();
  const std::size_t L = num_layers();
  const Eigen::Index batch = x.cols();
  prepare_impl(ws, batch);
  gradient.resize(static_cast<Eigen::Index>(num_parameters_));

  forward_impl<T>(params, x, ws, true);

  // Loss and output error: dMSE/da_L = 2 (a_L - y) / (n_L * batch).
  ws.delta[L] = ws.a[L] - y;
  const T count = static_cast<T>(ws.delta[L].size());
  const T loss = ws.delta[L].squaredNorm() / count;
  ws.delta[L] *= T(2) / count;

  // Backward.
  for (std::size_t l = L; l >= 1; --l) {
    multiply_derivative(activation(l), ws.a[l], ws.delta[l]);
    const Eigen::Index in = sizes_[l - 1], out = sizes_[l];
    const ConstMap w(params.data() + weight_offset(l - 1), out, in);
    Eigen::Map<Matrix<T>> gw(gradient.data() + weight_offset(l - 1), out, in);
    Eigen::Map<Vector<T>> gb(gradient.data() + weight_offset(l - 1) + in * out, out);
    const Matrix<T>& input = dropout_[l - 1] ? ws.d[l - 1] : ws.a[l - 1];
    kernels::multiply(k, ws.delta[l], false, input, true, gw);
    gb.noalias() = ws.delta[l].rowwise().sum();
    if (l > 1) {
      kernels::multiply(k, w, true, ws.delta[l], false, ws.delta[l - 1]);
      if (dropout_[l - 1]) ws.delta[l - 1].array() *= ws.mask[l - 1].array();
    }
  }
  return loss;
}

bool Mlp::has_any_dropout() const {
  return std::find(dropout_.begin(), dropout_.end(), true) != dropout_.end();
}

Eigen::MatrixXd Mlp::predict_mc(const Eigen::VectorXd& params, const Eigen::MatrixXd& x,
                                std::size_t passes, Rng& rng) const {
  if (!has_any_dropout()) return predict(params, x);
  if (x.rows() != sizes_.front()) {
    throw Error("Mlp::predict_mc: expected " + std::to_string(sizes_.front()) +
                " input rows, got " + std::to_string(x.rows()));
  }
  if (passes < 1) throw Error("Mlp::predict_mc: at least one pass");
  Eigen::MatrixXd mean = Eigen::MatrixXd::Zero(sizes_.back(), x.cols());
  Workspace ws;
  for (Eigen::Index start = 0; start < x.cols(); start += kMcBlock) {
    const Eigen::Index n = std::min(kMcBlock, x.cols() - start);
    prepare(ws, n);
    for (std::size_t k = 0; k < passes; ++k) {
      draw_dropout_masks(ws, rng);
      forward(params, x.middleCols(start, n), ws, true);
      mean.middleCols(start, n) += ws.a.back();
    }
  }
  return mean / static_cast<double>(passes);
}

Eigen::MatrixXd Mlp::infer(const Eigen::VectorXd& params, const Eigen::MatrixXd& x,
                           DropoutInference inference, Rng& rng) const {
  return inference == DropoutInference::mc ? predict_mc(params, x, options_.dropout_mc_samples, rng)
                                           : predict(params, x);
}

double Mlp::loss_and_gradient(const Eigen::VectorXd& params,
                              const Eigen::Ref<const Eigen::MatrixXd>& x,
                              const Eigen::Ref<const Eigen::MatrixXd>& y, Workspace& ws,
                              Eigen::VectorXd& gradient) const {
  return loss_and_gradient_impl<double>(params, x, y, ws, gradient);
}

float Mlp::loss_and_gradient(const Eigen::VectorXf& params,
                             const Eigen::Ref<const Eigen::MatrixXf>& x,
                             const Eigen::Ref<const Eigen::MatrixXf>& y, Workspace32& ws,
                             Eigen::VectorXf& gradient) const {
  return loss_and_gradient_impl<float>(params, x, y, ws, gradient);
}

template <class T>
void Mlp::forward_impl(const Vector<T>& params, const Eigen::Ref<const Matrix<T>>& x,
                       MlpWorkspace<T>& ws, bool masked) const {
  using ConstMap = Eigen::Map<const Matrix<T>>;
  using ConstVectorMap = Eigen::Map<const Vector<T>>;
  const kernels::Table& k = kernels::active();
  if (x.data() != ws.a[0].data()) ws.a[0] = x;  // a caller may gather into ws.a[0] itself
  for (std::size_t l = 1; l <= num_layers(); ++l) {
    const Eigen::Index in = sizes_[l - 1], out = sizes_[l];
    const ConstMap w(params.data() + weight_offset(l - 1), out, in);
    const ConstVectorMap b(params.data() + weight_offset(l - 1) + in * out, out);
    const Matrix<T>& input = masked && dropout_[l - 1] ? ws.d[l - 1] : ws.a[l - 1];
    kernels::multiply(k, w, false, input, false, ws.a[l]);
    ws.a[l].colwise() += b;
    apply_activation(activation(l), ws.a[l]);
    if (masked && dropout_[l]) ws.d[l] = ws.a[l].cwiseProduct(ws.mask[l]);
  }
}

void Mlp::forward(const Eigen::VectorXd& params, const Eigen::Ref<const Eigen::MatrixXd>& x,
                  Workspace& ws, bool masked) const {
  forward_impl<double>(params, x, ws, masked);
}

void Mlp::output_jacobian(const Eigen::VectorXd& params, const Eigen::Ref<const Eigen::MatrixXd>& x,
                          Workspace& ws, Eigen::Ref<Eigen::MatrixXd> outputs,
                          Eigen::Ref<Eigen::MatrixXd> jacobian) const {
  const std::size_t L = num_layers();
  const Eigen::Index batch = x.cols(), n_out = sizes_.back();
  if (x.rows() != sizes_.front() || outputs.rows() != n_out || outputs.cols() != batch ||
      jacobian.rows() != batch * n_out ||
      jacobian.cols() != static_cast<Eigen::Index>(num_parameters_)) {
    throw Error("Mlp::output_jacobian: sizes do not match the network");
  }
  prepare(ws, batch);
  forward(params, x, ws, false);
  outputs = ws.a[L];
  // Activations with one sample per row, so that each Jacobian column is an
  // elementwise product of two contiguous columns.
  std::vector<Eigen::MatrixXd> a_t(L);
  for (std::size_t l = 0; l < L; ++l) a_t[l] = ws.a[l].transpose();
  Eigen::MatrixXd delta_t;
  const kernels::Table& kernel = kernels::active();
  for (Eigen::Index k = 0; k < n_out; ++k) {
    // delta_L = e_k f_L'(z_L): the derivative of output k alone.
    ws.delta[L].setZero();
    ws.delta[L].row(k).setOnes();
    multiply_derivative(options_.output_activation, ws.a[L], ws.delta[L]);
    for (std::size_t l = L; l >= 1; --l) {
      const Eigen::Index in = sizes_[l - 1], out = sizes_[l];
      const Eigen::Index offset = weight_offset(l - 1);
      delta_t = ws.delta[l].transpose();
      kernel.mlp_jacobian_columns(batch, in, out, n_out, k, delta_t.data(), a_t[l - 1].data(),
                                  jacobian.data(), jacobian.outerStride(), offset);
      if (l > 1) {
        const MapMatrix w(params.data() + offset, out, in);
        kernels::multiply(kernel, w, true, ws.delta[l], false, ws.delta[l - 1]);
        multiply_derivative(options_.hidden_activation, ws.a[l - 1], ws.delta[l - 1]);
      }
    }
  }
}

}  // namespace cnclab
