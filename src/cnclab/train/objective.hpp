#pragma once
// Objectives trainers minimise. Trainers see only these interfaces and a flat
// parameter vector, never a network (the ensmallen/Ceres split).
#include <Eigen/Core>
#include <cstddef>
#include <span>

#include "cnclab/core/rng.hpp"
#include "cnclab/nn/mlp.hpp"

namespace cnclab {

// A loss that is a mean over samples, evaluated on mini-batches.
class SeparableObjective {
 public:
  virtual ~SeparableObjective() = default;
  virtual std::size_t num_samples() const = 0;
  virtual std::size_t num_parameters() const = 0;
  // Mean loss over the samples in `batch` (training mode) and its gradient
  // with respect to `params` (overwritten).
  virtual double loss_and_gradient(const Eigen::VectorXd& params,
                                   std::span<const std::size_t> batch,
                                   Eigen::VectorXd& gradient) = 0;
};

// MSE regression of an Mlp on (already normalised) inputs and targets, one
// sample per column. Dropout masks are drawn from `dropout_rng` per batch.
class MlpRegressionObjective : public SeparableObjective {
 public:
  MlpRegressionObjective(const Mlp& mlp, const Eigen::MatrixXd& inputs,
                         const Eigen::MatrixXd& targets, Rng& dropout_rng);
  std::size_t num_samples() const override { return static_cast<std::size_t>(inputs_.cols()); }
  std::size_t num_parameters() const override { return mlp_.num_parameters(); }
  double loss_and_gradient(const Eigen::VectorXd& params, std::span<const std::size_t> batch,
                           Eigen::VectorXd& gradient) override;

 private:
  const Mlp& mlp_;
  const Eigen::MatrixXd& inputs_;
  const Eigen::MatrixXd& targets_;
  Rng& dropout_rng_;
  Mlp::Workspace workspace_;
  Eigen::MatrixXd x_batch_, y_batch_;
  bool any_dropout_ = false;
};

}  // namespace cnclab
