#include "cnclab/nn/constant_predictions.hpp"

#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

double population_variance(const Eigen::Ref<const Eigen::RowVectorXd>& v) {
  return (v.array() - v.mean()).square().mean();
}

}  // namespace

std::vector<Eigen::Index> constant_prediction_rows(const Eigen::MatrixXd& predictions,
                                                   const Eigen::MatrixXd& targets) {
  if (predictions.rows() != targets.rows() || predictions.cols() != targets.cols()) {
    throw Error("constant predictions: predictions are " + std::to_string(predictions.rows()) +
                "x" + std::to_string(predictions.cols()) + " but targets " +
                std::to_string(targets.rows()) + "x" + std::to_string(targets.cols()));
  }
  std::vector<Eigen::Index> rows;
  if (predictions.cols() < 2) return rows;
  for (Eigen::Index r = 0; r < predictions.rows(); ++r) {
    const auto p = predictions.row(r);
    if (!p.allFinite()) continue;  // max/min are undefined with NaN
    const bool constant = p.maxCoeff() == p.minCoeff();
    const bool tiny =
        population_variance(p) < kConstantPredictionRatio * population_variance(targets.row(r));
    if (constant || tiny) rows.push_back(r);
  }
  return rows;
}

}  // namespace cnclab
