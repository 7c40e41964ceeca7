#include "cnclab/nn/minmax.hpp"

#include <cmath>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {

MinMaxNormaliser::MinMaxNormaliser(double low, double high) : low_(low), high_(high) {
  if (!std::isfinite(low) || !std::isfinite(high) || !(low < high)) {
    throw Error("min-max: range [" + std::to_string(low) + ", " + std::to_string(high) +
                "] must be finite with low < high");
  }
}

MinMaxNormaliser::MinMaxNormaliser(Eigen::VectorXd min, Eigen::VectorXd max, double low,
                                   double high)
    : MinMaxNormaliser(low, high) {
  if (min.size() != max.size()) throw Error("min-max: min and max sizes differ");
  for (Eigen::Index i = 0; i < min.size(); ++i) {
    if (!std::isfinite(min[i]) || !std::isfinite(max[i]) || !(min[i] <= max[i])) {
      throw Error("min-max: feature " + std::to_string(i) + " has min " + std::to_string(min[i]) +
                  " and max " + std::to_string(max[i]) + " (must be finite with min <= max)");
    }
  }
  min_ = std::move(min);
  max_ = std::move(max);
  set_gain();
}

void MinMaxNormaliser::fit(const Eigen::MatrixXd& data) {
  if (data.cols() < 1) throw Error("min-max: need at least 1 sample to fit");
  for (Eigen::Index i = 0; i < data.rows(); ++i) {
    if (!data.row(i).allFinite()) {
      throw Error("min-max: feature " + std::to_string(i) + " has non-finite values");
    }
  }
  min_ = data.rowwise().minCoeff();
  max_ = data.rowwise().maxCoeff();
  set_gain();
}

void MinMaxNormaliser::set_gain() {
  gain_.resize(min_.size());
  constant_.clear();
  for (Eigen::Index i = 0; i < min_.size(); ++i) {
    const double span = max_[i] - min_[i];
    gain_[i] = span > 0 ? (high_ - low_) / span : 0.0;
    if (!(span > 0)) constant_.push_back(i);
  }
}

void MinMaxNormaliser::check_rows(const Eigen::MatrixXd& data) const {
  if (data.rows() != min_.size()) {
    throw Error("min-max: fitted on " + std::to_string(min_.size()) + " features, got " +
                std::to_string(data.rows()));
  }
}

Eigen::MatrixXd MinMaxNormaliser::transform(const Eigen::MatrixXd& data) const {
  check_rows(data);
  return ((data.colwise() - min_).array().colwise() * gain_.array()) + low_;
}

Eigen::MatrixXd MinMaxNormaliser::inverse_transform(const Eigen::MatrixXd& scaled) const {
  check_rows(scaled);
  Eigen::MatrixXd out = scaled;
  for (Eigen::Index i = 0; i < out.rows(); ++i) {
    // A constant feature maps back to its value whatever the scaled input.
    if (gain_[i] > 0) {
      out.row(i) = ((scaled.row(i).array() - low_) / gain_[i] + min_[i]).matrix();
    } else {
      out.row(i).setConstant(min_[i]);
    }
  }
  return out;
}

}  // namespace cnclab
