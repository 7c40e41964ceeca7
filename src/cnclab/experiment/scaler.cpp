#include "cnclab/experiment/scaler.hpp"

namespace cnclab {

FeatureScaler FeatureScaler::fit(Scaling kind, const std::array<double, 2>& range,
                                 const Eigen::MatrixXd& data) {
  FeatureScaler s;
  if (kind == Scaling::zscore) {
    s.zscore_.emplace();
    s.zscore_->fit(data);
  } else if (kind == Scaling::minmax) {
    s.minmax_.emplace(range[0], range[1]);
    s.minmax_->fit(data);
  }
  return s;
}

FeatureScaler FeatureScaler::from_record(const ScalingRecord& r) {
  FeatureScaler s;
  if (r.mean.size()) s.zscore_.emplace(r.mean, r.std);
  if (r.min.size()) s.minmax_.emplace(r.min, r.max, r.low, r.high);
  return s;
}

Eigen::MatrixXd FeatureScaler::transform(const Eigen::MatrixXd& data) const {
  return zscore_ ? zscore_->transform(data) : minmax_ ? minmax_->transform(data) : data;
}

Eigen::MatrixXd FeatureScaler::inverse_transform(const Eigen::MatrixXd& scaled) const {
  return zscore_   ? zscore_->inverse_transform(scaled)
         : minmax_ ? minmax_->inverse_transform(scaled)
                   : scaled;
}

ScalingRecord FeatureScaler::record() const {
  ScalingRecord r;
  if (zscore_) {
    r.mean = zscore_->mean();
    r.std = zscore_->std();
  }
  if (minmax_) {
    r.min = minmax_->min();
    r.max = minmax_->max();
    r.low = minmax_->low();
    r.high = minmax_->high();
  }
  return r;
}

}  // namespace cnclab
