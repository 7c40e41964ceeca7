#include "cnclab/train/objective.hpp"

#include "cnclab/core/error.hpp"

namespace cnclab {

MlpRegressionObjective::MlpRegressionObjective(const Mlp& mlp, const Eigen::MatrixXd& inputs,
                                               const Eigen::MatrixXd& targets, Rng& dropout_rng)
    : mlp_(mlp), inputs_(inputs), targets_(targets), dropout_rng_(dropout_rng) {
  const auto& sizes = mlp.layer_sizes();
  if (inputs.rows() != sizes.front() || targets.rows() != sizes.back() ||
      inputs.cols() != targets.cols()) {
    throw Error("MlpRegressionObjective: network " + std::to_string(sizes.front()) + " -> " +
                std::to_string(sizes.back()) + " but data " + std::to_string(inputs.rows()) +
                " x " + std::to_string(inputs.cols()) + " -> " + std::to_string(targets.rows()) +
                " x " + std::to_string(targets.cols()));
  }
  for (std::size_t l = 0; l < sizes.size(); ++l) any_dropout_ = any_dropout_ || mlp.has_dropout(l);
}

float SeparableObjective::loss_and_gradient_float32(const Eigen::VectorXf&,
                                                    std::span<const std::size_t>,
                                                    Eigen::VectorXf&) {
  throw Error("this objective has no float32 evaluation (precision: float64)");
}

template <class T, class Workspace>
T MlpRegressionObjective::loss_and_gradient_impl(
    const Eigen::Matrix<T, Eigen::Dynamic, 1>& params,
    const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>& inputs,
    const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>& targets,
    std::span<const std::size_t> batch, Workspace& ws,
    Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>& y_batch,
    Eigen::Matrix<T, Eigen::Dynamic, 1>& gradient) {
  const auto b = static_cast<Eigen::Index>(batch.size());
  if (y_batch.cols() != b) y_batch.resize(targets.rows(), b);
  // The inputs are gathered into the network's input activations a_0, which
  // Mlp::loss_and_gradient then uses in place (no second copy).
  mlp_.prepare(ws, b);
  auto& x_batch = ws.a[0];
  // The batch's columns sit anywhere in the data (a shuffled order), so each
  // one is a cache miss unless asked for early: the column kPrefetchAhead
  // places on is requested while this one is copied.
  constexpr std::size_t kPrefetchAhead = 8;
  const auto line = static_cast<Eigen::Index>(64 / sizeof(T));
  for (Eigen::Index j = 0; j < b; ++j) {
    const auto at = static_cast<std::size_t>(j);
    if (at + kPrefetchAhead < batch.size()) {
      const T* ahead =
          inputs.data() + static_cast<Eigen::Index>(batch[at + kPrefetchAhead]) * inputs.rows();
      for (Eigen::Index r = 0; r < inputs.rows(); r += line) __builtin_prefetch(ahead + r);
    }
    const auto col = static_cast<Eigen::Index>(batch[at]);
    x_batch.col(j) = inputs.col(col);
    y_batch.col(j) = targets.col(col);
  }
  if (any_dropout_) mlp_.draw_dropout_masks(ws, dropout_rng_);
  return mlp_.loss_and_gradient(params, x_batch, y_batch, ws, gradient);
}

double MlpRegressionObjective::loss_and_gradient(const Eigen::VectorXd& params,
                                                 std::span<const std::size_t> batch,
                                                 Eigen::VectorXd& gradient) {
  return loss_and_gradient_impl<double>(params, inputs_, targets_, batch, workspace_, y_batch_,
                                        gradient);
}

float MlpRegressionObjective::loss_and_gradient_float32(const Eigen::VectorXf& params,
                                                        std::span<const std::size_t> batch,
                                                        Eigen::VectorXf& gradient) {
  if (inputs32_.size() != inputs_.size()) {
    inputs32_ = inputs_.cast<float>();
    targets32_ = targets_.cast<float>();
  }
  return loss_and_gradient_impl<float>(params, inputs32_, targets32_, batch, workspace32_,
                                       y_batch32_, gradient);
}

}  // namespace cnclab
