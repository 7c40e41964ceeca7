#pragma once
// Least-squares regression of an Mlp for the Levenberg-Marquardt trainers:
// residual s n_L + k = y_k(x_s) - t_{k,s} (network output minus target, one
// sample per column of inputs/targets), Jacobian from Mlp::output_jacobian.
// E_D = e^T e is the plain sum of squared errors over all target elements.
#include <Eigen/Core>

#include "cnclab/nn/mlp.hpp"
#include "cnclab/train/residual_objective.hpp"

namespace cnclab {

class MlpResidualObjective : public ResidualObjective {
 public:
  // Throws if the sizes do not match or the network has dropout (LM needs a
  // deterministic objective).
  MlpResidualObjective(const Mlp& mlp, const Eigen::MatrixXd& inputs,
                       const Eigen::MatrixXd& targets);
  Eigen::Index num_residuals() const override { return targets_.size(); }
  Eigen::Index num_parameters() const override {
    return static_cast<Eigen::Index>(mlp_.num_parameters());
  }
  Eigen::Index row_granularity() const override { return targets_.rows(); }
  void evaluate(const Eigen::VectorXd& params, Eigen::Index first, Eigen::Index count,
                Eigen::Ref<Eigen::VectorXd> residuals, Eigen::MatrixXd* jacobian) override;

 private:
  const Mlp& mlp_;
  const Eigen::MatrixXd& inputs_;
  const Eigen::MatrixXd& targets_;
  Mlp::Workspace workspace_;
  Eigen::MatrixXd outputs_;
};

}  // namespace cnclab
