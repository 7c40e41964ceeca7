#include "cnclab/train/mlp_residuals.hpp"

#include "cnclab/core/error.hpp"

namespace cnclab {

MlpResidualObjective::MlpResidualObjective(const Mlp& mlp, const Eigen::MatrixXd& inputs,
                                           const Eigen::MatrixXd& targets)
    : mlp_(mlp), inputs_(inputs), targets_(targets) {
  const auto& sizes = mlp.layer_sizes();
  if (inputs.rows() != sizes.front() || targets.rows() != sizes.back() ||
      inputs.cols() != targets.cols() || inputs.cols() < 1) {
    throw Error("MlpResidualObjective: network " + std::to_string(sizes.front()) + " -> " +
                std::to_string(sizes.back()) + " but data " + std::to_string(inputs.rows()) +
                " x " + std::to_string(inputs.cols()) + " -> " + std::to_string(targets.rows()) +
                " x " + std::to_string(targets.cols()));
  }
  for (std::size_t l = 0; l < sizes.size(); ++l) {
    if (mlp.has_dropout(l)) {
      throw Error(
          "Levenberg-Marquardt training needs a deterministic network: dropout "
          "(keep probability < 1) is not supported");
    }
  }
}

void MlpResidualObjective::evaluate(const Eigen::VectorXd& params, Eigen::Index first,
                                    Eigen::Index count, Eigen::Ref<Eigen::VectorXd> residuals,
                                    Eigen::MatrixXd* jacobian) {
  const Eigen::Index n_out = targets_.rows();
  const Eigen::Index s0 = first / n_out, samples = count / n_out;
  const auto x = inputs_.middleCols(s0, samples);
  if (jacobian) {
    outputs_.resize(n_out, samples);
    mlp_.output_jacobian(params, x, workspace_, outputs_, *jacobian);
  } else {
    outputs_ = mlp_.predict(params, x);
  }
  // Targets are column-major, so rows [first, first + count) are contiguous.
  residuals = Eigen::Map<const Eigen::VectorXd>(outputs_.data(), count) -
              Eigen::Map<const Eigen::VectorXd>(targets_.data() + first, count);
}

}  // namespace cnclab
