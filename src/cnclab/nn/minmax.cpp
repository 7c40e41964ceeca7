#include "cnclab/nn/minmax.hpp"

#include <cmath>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {

MinMaxNormaliser::MinMaxNormaliser(double y_min, double y_max) : y_min_(y_min), y_max_(y_max) {
  if (!std::isfinite(y_min) || !std::isfinite(y_max) || !(y_min < y_max)) {
    throw Error("min-max: range [" + std::to_string(y_min) + ", " + std::to_string(y_max) +
                "] must be finite with y_min < y_max");
  }
}

MinMaxNormaliser::MinMaxNormaliser(Eigen::VectorXd x_min, Eigen::VectorXd x_max, double y_min,
                                   double y_max)
    : MinMaxNormaliser(y_min, y_max) {
  if (x_min.size() != x_max.size()) throw Error("min-max: min and max sizes differ");
  for (Eigen::Index i = 0; i < x_min.size(); ++i) {
    if (!std::isfinite(x_min[i]) || !std::isfinite(x_max[i]) || !(x_min[i] <= x_max[i])) {
      throw Error("min-max: feature " + std::to_string(i) + " has min " + std::to_string(x_min[i]) +
                  " and max " + std::to_string(x_max[i]) + " (must be finite with min <= max)");
    }
  }
  x_min_ = std::move(x_min);
  x_max_ = std::move(x_max);
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
  gain_.resize(x_min_.size());
  offset_.resize(x_min_.size());
  constant_.clear();
  for (Eigen::Index i = 0; i < x_min_.size(); ++i) {
    const double span = x_max_[i] - x_min_[i];
    if (span > 0) {
      gain_[i] = (y_max_ - y_min_) / span;
      offset_[i] = x_min_[i];
    } else {
      gain_[i] = 1.0;
      offset_[i] = y_min_;
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
  return ((data.colwise() - offset_).array().colwise() * gain_.array()) + y_min_;
}

Eigen::MatrixXd MinMaxNormaliser::inverse_transform(const Eigen::MatrixXd& scaled) const {
  check_rows(scaled);
  return ((scaled.array() - y_min_).colwise() / gain_.array()).matrix().colwise() + offset_;
}

}  // namespace cnclab
