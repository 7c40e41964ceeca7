#pragma once
// Fully connected feedforward network (multilayer perceptron) over one flat
// parameter vector, with inverted dropout (PyTorch semantics).
//
// Parameter layout, layer by layer l = 1..L: W_l (n_l x n_{l-1}, column-major)
// then b_l (n_l). Batches hold one sample per column.
//
// Forward (seed 000 Eqs. 2-3, 12-13):
//   a_0 = x;  z_l = W_l d_{l-1} + b_l;  a_l = f_l(z_l);  d_l = a_l * r_l / p
// with r_l ~ Bernoulli(p) on hidden layers that have dropout (p = keep
// probability; r = 1, no scaling, at evaluation and on other layers).
// Loss: MSE = mean over all outputs and samples of (a_L - y)^2 (PyTorch's
// MSELoss 'mean').
#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "cnclab/core/rng.hpp"
#include "cnclab/nn/activation.hpp"
#include "cnclab/nn/initializer.hpp"

namespace cnclab {

enum class DropoutPlacement {
  // On the output of every hidden layer that feeds another hidden layer
  // (seed 000 step 6: "use Dropout in every two hidden layers"); with hidden
  // [28, 20]: after the 28-unit layer only.
  between_hidden,
  // On the output of every hidden layer, the last included (PyTorch's usual
  // Linear-ReLU-Dropout stacking).
  after_every_hidden,
};
std::string to_string(DropoutPlacement p);

// How a network with dropout is evaluated (the predictions and metrics a run
// reports). Seed 000 does not say; both are in use for regression:
enum class DropoutInference {
  // One pass with every r = 1 (inverted dropout's usual evaluation,
  // PyTorch's eval()): the network's weights at their expected scale.
  deterministic,
  // Monte-Carlo dropout (Gal & Ghahramani, ICML 2016): the mean of N passes,
  // each with new masks r ~ Bernoulli(p) as in training. Through a nonlinear
  // network the mean of the masked passes is not the deterministic pass (the
  // variance shift of dropout), so the two can differ in accuracy.
  mc,
};
std::string to_string(DropoutInference i);

struct MlpOptions {
  std::size_t inputs = 1;
  std::vector<std::size_t> hidden = {28, 20};  // seed 000: two hidden layers, 28 and 20
  std::size_t outputs = 1;
  Activation hidden_activation = Activation::relu;
  Activation output_activation = Activation::linear;
  // Probability of KEEPING a unit (seed 000 Eq. 13: P(r = 1) = p). 1 = no dropout.
  double dropout_keep_probability = 1.0;
  DropoutPlacement dropout_placement = DropoutPlacement::between_hidden;
  DropoutInference dropout_inference = DropoutInference::deterministic;
  // N of DropoutInference::mc: masks averaged per sample. 100 keeps the
  // Monte-Carlo error of the mean at a tenth of one pass's spread (1/sqrt(N)).
  std::size_t dropout_mc_samples = 100;
  Initializer weights{Initializer::Kind::normal, 0.0, 1.0};  // seed 000: N(0, 1)
  // Seed 000 draws biases from U(c, d) without giving c and d; U(0, 0.1) is
  // our choice (small, positive: keeps ReLU units active at the start).
  Initializer biases{Initializer::Kind::uniform, 0.0, 1.0, 0.0, 0.1};

  // Sizes >= 1, keep probability in (0, 1], mc samples in [1, 1e6],
  // initialisers valid.
  void validate() const;
};

// Buffers of an Mlp for one batch size, in double or float (float32
// training, train/); reused across mini-batches (no allocation in the
// training loop).
template <class T>
struct MlpWorkspace {
  using Matrix = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
  std::vector<Matrix> a;     // activations a_l (pre-dropout), l = 0..L
  std::vector<Matrix> d;     // dropped-out activations d_l (hidden layers with dropout)
  std::vector<Matrix> mask;  // r_l / p, same shape as d_l
  std::vector<Matrix> delta;
  Eigen::Index batch = 0;
};

// The products and activations run through nn/kernels.hpp, at this
// process's instruction-set level.
class Mlp {
 public:
  using Workspace = MlpWorkspace<double>;
  using Workspace32 = MlpWorkspace<float>;

  explicit Mlp(MlpOptions options);  // validates

  const MlpOptions& options() const { return options_; }
  // n_0 = inputs, n_1.. = hidden, n_L = outputs.
  const std::vector<Eigen::Index>& layer_sizes() const { return sizes_; }
  std::size_t num_layers() const { return sizes_.size() - 1; }
  // sum_l (n_{l-1} + 1) n_l
  std::size_t num_parameters() const { return num_parameters_; }
  bool has_dropout(std::size_t layer) const { return dropout_[layer]; }

  // Draws all weights and biases with the configured initialisers.
  void initialise(Eigen::VectorXd& params, Rng& rng) const;

  // Evaluation-mode outputs (no dropout).
  Eigen::MatrixXd predict(const Eigen::VectorXd& params, const Eigen::MatrixXd& x) const;
  // Monte-Carlo dropout: the mean over `passes` training-mode forward passes
  // of x, each with new masks (entries 0 or 1/p). Samples are taken in blocks
  // of kMcBlock columns; for each block, pass after pass, the masks are drawn
  // from `rng` as draw_dropout_masks does (layer by layer, column-major).
  // Without dropout layers it is predict() and rng is not used.
  Eigen::MatrixXd predict_mc(const Eigen::VectorXd& params, const Eigen::MatrixXd& x,
                             std::size_t passes, Rng& rng) const;
  static constexpr Eigen::Index kMcBlock = 4096;
  // The predictions under `inference`: predict(), or predict_mc() with
  // options().dropout_mc_samples passes (rng: the run's own stream for it).
  Eigen::MatrixXd infer(const Eigen::VectorXd& params, const Eigen::MatrixXd& x,
                        DropoutInference inference, Rng& rng) const;
  // Whether any layer has dropout (keep probability < 1 and a layer it applies to).
  bool has_any_dropout() const;

  // Sizes the workspace for batches of `batch` samples.
  void prepare(Workspace& ws, Eigen::Index batch) const;
  void prepare(Workspace32& ws, Eigen::Index batch) const;
  // New inverted-dropout masks in ws (entries 0 or 1/p), for the batch size
  // ws was prepared for. Both precisions draw the same numbers from `rng`.
  void draw_dropout_masks(Workspace& ws, Rng& rng) const;
  void draw_dropout_masks(Workspace32& ws, Rng& rng) const;
  // Training-mode MSE and its gradient (overwritten) for the batch x, y,
  // using the masks currently in ws. x: inputs x batch, y: outputs x batch;
  // x may be ws.a[0] itself, filled after prepare() (then nothing is copied).
  // The float overload computes in float throughout (float32 training).
  double loss_and_gradient(const Eigen::VectorXd& params,
                           const Eigen::Ref<const Eigen::MatrixXd>& x,
                           const Eigen::Ref<const Eigen::MatrixXd>& y, Workspace& ws,
                           Eigen::VectorXd& gradient) const;
  float loss_and_gradient(const Eigen::VectorXf& params, const Eigen::Ref<const Eigen::MatrixXf>& x,
                          const Eigen::Ref<const Eigen::MatrixXf>& y, Workspace32& ws,
                          Eigen::VectorXf& gradient) const;

  // Evaluation-mode outputs of the batch x (written to `outputs`, n_L x b) and
  // the exact Jacobian of every output with respect to the parameters, by one
  // backpropagation per output unit: row s n_L + k of `jacobian`
  // ((b n_L) x num_parameters()) is d y_k(x_s) / dw. Dropout is not applied.
  void output_jacobian(const Eigen::VectorXd& params, const Eigen::Ref<const Eigen::MatrixXd>& x,
                       Workspace& ws, Eigen::Ref<Eigen::MatrixXd> outputs,
                       Eigen::Ref<Eigen::MatrixXd> jacobian) const;

 private:
  // Forward pass of x into ws.a (ws prepared for x.cols()): evaluation mode,
  // or with `masked` training mode, the masks in ws applied into ws.d.
  void forward(const Eigen::VectorXd& params, const Eigen::Ref<const Eigen::MatrixXd>& x,
               Workspace& ws, bool masked) const;

  Eigen::Index weight_offset(std::size_t layer) const { return offsets_[layer]; }
  Activation activation(std::size_t layer) const {
    return layer == num_layers() ? options_.output_activation : options_.hidden_activation;
  }
  template <class T>
  void forward_impl(const Eigen::Matrix<T, Eigen::Dynamic, 1>& params,
                    const Eigen::Ref<const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>>& x,
                    MlpWorkspace<T>& ws, bool masked) const;
  template <class T>
  void prepare_impl(MlpWorkspace<T>& ws, Eigen::Index batch) const;
  template <class T>
  void draw_masks_impl(MlpWorkspace<T>& ws, Rng& rng) const;
  template <class T>
  T loss_and_gradient_impl(
      const Eigen::Matrix<T, Eigen::Dynamic, 1>& params,
      const Eigen::Ref<const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>>& x,
      const Eigen::Ref<const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>>& y,
      MlpWorkspace<T>& ws, Eigen::Matrix<T, Eigen::Dynamic, 1>& gradient) const;

  MlpOptions options_;
  std::vector<Eigen::Index> sizes_;
  std::vector<Eigen::Index> offsets_;  // start of W_l in the flat vector, l = 1..L (index l-1)
  std::vector<bool> dropout_;          // per layer l = 0..L: dropout on a_l
  std::size_t num_parameters_ = 0;
};

}  // namespace cnclab
