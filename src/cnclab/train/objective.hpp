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
  // The same computed in float throughout (float32 training, sgdm.hpp);
  // whether this objective has it.
  virtual bool has_float32() const { return false; }
  // (A name of its own: an override of the double one alone hides no
  // overload.)
  virtual float loss_and_gradient_float32(const Eigen::VectorXf& params,
                                          std::span<const std::size_t> batch,
                                          Eigen::VectorXf& gradient);
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
  // In float: the data are converted once, on the first call.
  bool has_float32() const override { return true; }
  float loss_and_gradient_float32(const Eigen::VectorXf& params, std::span<const std::size_t> batch,
                                  Eigen::VectorXf& gradient) override;

 private:
  template <class T, class Workspace>
  T loss_and_gradient_impl(const Eigen::Matrix<T, Eigen::Dynamic, 1>& params,
                           const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>& inputs,
                           const Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>& targets,
                           std::span<const std::size_t> batch, Workspace& ws,
                           Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>& y_batch,
                           Eigen::Matrix<T, Eigen::Dynamic, 1>& gradient);

  const Mlp& mlp_;
  const Eigen::MatrixXd& inputs_;
  const Eigen::MatrixXd& targets_;
  Rng& dropout_rng_;
  Mlp::Workspace workspace_;
  Eigen::MatrixXd y_batch_;  // the batch's targets (its inputs go into the workspace's a_0)
  Mlp::Workspace32 workspace32_;
  Eigen::MatrixXf inputs32_, targets32_, y_batch32_;
  bool any_dropout_ = false;
};

}  // namespace cnclab
