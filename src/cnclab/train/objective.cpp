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

double MlpRegressionObjective::loss_and_gradient(const Eigen::VectorXd& params,
                                                 std::span<const std::size_t> batch,
                                                 Eigen::VectorXd& gradient) {
  const auto b = static_cast<Eigen::Index>(batch.size());
  if (x_batch_.cols() != b) {
    x_batch_.resize(inputs_.rows(), b);
    y_batch_.resize(targets_.rows(), b);
  }
  for (Eigen::Index j = 0; j < b; ++j) {
    const auto col = static_cast<Eigen::Index>(batch[static_cast<std::size_t>(j)]);
    x_batch_.col(j) = inputs_.col(col);
    y_batch_.col(j) = targets_.col(col);
  }
  mlp_.prepare(workspace_, b);
  if (any_dropout_) mlp_.draw_dropout_masks(workspace_, dropout_rng_);
  return mlp_.loss_and_gradient(params, x_batch_, y_batch_, workspace_, gradient);
}

}  // namespace cnclab
