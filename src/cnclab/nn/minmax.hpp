#pragma once
// Min-max normalisation per feature, MATLAB mapminmax semantics, to a
// configurable range [y_min, y_max] (default [-1, 1], mapminmax's):
//   y = (y_max - y_min) (x - x_min) / (x_max - x_min) + y_min,
// x_min, x_max per feature from the TRAINING split. A sigmoid output layer
// needs a range inside (0, 1), e.g. [0.1, 0.9] (seed 004's networks). A
// constant feature (x_max = x_min) is passed through unchanged, y = x, as
// MATLAB documents ("If xmax=xmin ... then y=x and no change occurs";
// mapminmax, Algorithms); constant_features() lists them. Values outside the
// fitted range map outside [y_min, y_max] (no clipping), as
// mapminmax('apply').
#include <Eigen/Core>
#include <vector>

namespace cnclab {

class MinMaxNormaliser {
 public:
  static constexpr double kYMin = -1.0;  // mapminmax default ymin
  static constexpr double kYMax = 1.0;   // mapminmax default ymax

  // y_min < y_max, both finite (else cnclab::Error).
  explicit MinMaxNormaliser(double y_min = kYMin, double y_max = kYMax);
  // From stored ranges (x_min <= x_max, finite, equal sizes).
  MinMaxNormaliser(Eigen::VectorXd x_min, Eigen::VectorXd x_max, double y_min = kYMin,
                   double y_max = kYMax);

  // data: features x samples, >= 1 sample, all finite (else cnclab::Error).
  void fit(const Eigen::MatrixXd& data);
  Eigen::MatrixXd transform(const Eigen::MatrixXd& data) const;
  Eigen::MatrixXd inverse_transform(const Eigen::MatrixXd& scaled) const;
  // One value of feature i (0 <= i < features(), unchecked), the same
  // arithmetic as transform / inverse_transform; no allocation (real-time use).
  double transform(Eigen::Index i, double x) const noexcept {
    return (x - offset_[i]) * gain_[i] + y_min_;
  }
  double inverse_transform(Eigen::Index i, double y) const noexcept {
    return (y - y_min_) / gain_[i] + offset_[i];
  }
  Eigen::Index features() const { return x_min_.size(); }

  const Eigen::VectorXd& x_min() const { return x_min_; }
  const Eigen::VectorXd& x_max() const { return x_max_; }
  double y_min() const { return y_min_; }
  double y_max() const { return y_max_; }
  // The arithmetic above: y = (x - offset) gain + y_min per feature (an
  // export writes the same constants).
  const Eigen::VectorXd& gain() const { return gain_; }
  const Eigen::VectorXd& offset() const { return offset_; }
  const std::vector<Eigen::Index>& constant_features() const { return constant_; }

 private:
  void set_gain();
  void check_rows(const Eigen::MatrixXd& data) const;
  double y_min_ = kYMin, y_max_ = kYMax;
  Eigen::VectorXd x_min_, x_max_;
  // y = (x - offset) gain + y_min; constant features: gain 1, offset y_min
  // (so y = x).
  Eigen::VectorXd gain_, offset_;
  std::vector<Eigen::Index> constant_;
};

}  // namespace cnclab
