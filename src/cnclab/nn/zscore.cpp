#include "cnclab/nn/zscore.hpp"

#include <cmath>

#include "cnclab/core/error.hpp"

namespace cnclab {

ZScoreNormaliser::ZScoreNormaliser(Eigen::VectorXd mean, Eigen::VectorXd std)
    : mean_(std::move(mean)), std_(std::move(std)) {
  if (mean_.size() != std_.size()) throw Error("z-score: mean and std sizes differ");
  for (Eigen::Index i = 0; i < std_.size(); ++i) {
    if (!(std_[i] > 0) || !std::isfinite(std_[i]) || !std::isfinite(mean_[i])) {
      throw Error("z-score: feature " + std::to_string(i) + " has mean " +
                  std::to_string(mean_[i]) + " and std " + std::to_string(std_[i]) +
                  " (std must be finite and > 0)");
    }
  }
}

void ZScoreNormaliser::fit(const Eigen::MatrixXd& data) {
  if (data.cols() < 2) {
    throw Error("z-score: need at least 2 samples to fit, got " + std::to_string(data.cols()));
  }
  for (Eigen::Index i = 0; i < data.rows(); ++i) {
    if (!data.row(i).allFinite()) {
      throw Error("z-score: feature " + std::to_string(i) + " has non-finite values");
    }
  }
  const double n = static_cast<double>(data.cols());
  mean_ = data.rowwise().sum() / n;
  std_ = ((data.colwise() - mean_).array().square().rowwise().sum() / (n - 1.0)).sqrt();
  constant_.clear();
  for (Eigen::Index i = 0; i < std_.size(); ++i) {
    if (!(std_[i] > 0)) {
      std_[i] = 1.0;
      constant_.push_back(i);
    }
  }
}

void ZScoreNormaliser::check_rows(const Eigen::MatrixXd& data) const {
  if (data.rows() != mean_.size()) {
    throw Error("z-score: fitted on " + std::to_string(mean_.size()) + " features, got " +
                std::to_string(data.rows()));
  }
}

Eigen::MatrixXd ZScoreNormaliser::transform(const Eigen::MatrixXd& data) const {
  check_rows(data);
  return (data.colwise() - mean_).array().colwise() / std_.array();
}

Eigen::MatrixXd ZScoreNormaliser::inverse_transform(const Eigen::MatrixXd& scaled) const {
  check_rows(scaled);
  return (scaled.array().colwise() * std_.array()).matrix().colwise() + mean_;
}

}  // namespace cnclab
