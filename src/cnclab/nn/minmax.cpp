#include "cnclab/nn/minmax.hpp"

#include <cmath>

#include "cnclab/core/error.hpp"

namespace cnclab {

MinMaxNormaliser::MinMaxNormaliser(Eigen::VectorXd x_min, Eigen::VectorXd x_max)
    : x_min_(std::move(x_min)), x_max_(std::move(x_max)) {
  if (x_min_.size() != x_max_.size()) throw Error("min-max: x_min and x_max sizes differ");
  for (Eigen::Index i = 0; i < x_min_.size(); ++i) {
    if (!std::isfinite(x_min_[i]) || !std::isfinite(x_max_[i]) || !(x_min_[i] <= x_max_[i])) {
      throw Error("min-max: feature " + std::to_string(i) + " has range [" +
                  std::to_string(x_min_[i]) + ", " + std::to_string(x_max_[i]) +
                  "] (must be finite with min <= max)");
    }
  }
  set_gain();
}

void MinMaxNormaliser::fit(const Eigen::MatrixXd& data) {
  if (data.cols() < 1) throw Error("min-max: need at least 1 sample to fit");
  for (Eigen::Index i = 0; i < data.rows(); ++i) {
    if (!data.row(i).allFinite()) {
      throw Error("min-max: feature " + std::to_string(i) + " has non-finite values");
    }
  }
  x_min_ = data.rowwise().minCoeff();
  x_max_ = data.rowwise().maxCoeff();
  set_gain();
}

void MinMaxNormaliser::set_gain() {
  const Eigen::Index n = x_min_.size();
  gain_.resize(n);
  offset_.resize(n);
  constant_.clear();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (x_max_[i] > x_min_[i]) {
      gain_[i] = (kYMax - kYMin) / (x_max_[i] - x_min_[i]);
      offset_[i] = x_min_[i];
    } else {
      gain_[i] = 1.0;
      offset_[i] = kYMin;
      constant_.push_back(i);
    }
  }
}

void MinMaxNormaliser::check_rows(const Eigen::MatrixXd& data) const {
  if (data.rows() != x_min_.size()) {
    throw Error("min-max: fitted on " + std::to_string(x_min_.size()) + " features, got " +
                std::to_string(data.rows()));
  }
}

Eigen::MatrixXd MinMaxNormaliser::transform(const Eigen::MatrixXd& data) const {
  check_rows(data);
  return ((data.colwise() - offset_).array().colwise() * gain_.array()) + kYMin;
}

Eigen::MatrixXd MinMaxNormaliser::inverse_transform(const Eigen::MatrixXd& scaled) const {
  check_rows(scaled);
  return ((scaled.array() - kYMin).colwise() / gain_.array()).matrix().colwise() + offset_;
}

}  // namespace cnclab
