#pragma once
// Min-max normalisation to [y_min, y_max] = [-1, 1] per feature, MATLAB
// mapminmax semantics (the normaliser trainbr users expect; seed 002 scales
// its data to [-1, 1]):
//   y = (y_max - y_min) (x - x_min) / (x_max - x_min) + y_min,
// x_min, x_max per feature from the TRAINING split. A constant feature
// (x_max = x_min) is passed through unchanged, y = x, as MATLAB documents
// ("If xmax=xmin ... then y=x and no change occurs"; mapminmax, Algorithms);
// constant_features() lists them. Values outside the fitted range map
// outside [-1, 1] (no clipping), as in mapminmax('apply').
#include <Eigen/Core>
#include <vector>

namespace cnclab {

class MinMaxNormaliser {
 public:
  static constexpr double kYMin = -1.0;  // mapminmax default ymin
  static constexpr double kYMax = 1.0;   // mapminmax default ymax

  MinMaxNormaliser() = default;
  // From stored ranges (x_min <= x_max, finite).
  MinMaxNormaliser(Eigen::VectorXd x_min, Eigen::VectorXd x_max);

  // data: features x samples, >= 1 sample, all finite (else cnclab::Error).
  void fit(const Eigen::MatrixXd& data);
  Eigen::MatrixXd transform(const Eigen::MatrixXd& data) const;
  Eigen::MatrixXd inverse_transform(const Eigen::MatrixXd& scaled) const;

  const Eigen::VectorXd& x_min() const { return x_min_; }
  const Eigen::VectorXd& x_max() const { return x_max_; }
  const std::vector<Eigen::Index>& constant_features() const { return constant_; }

 private:
  void set_gain();
  void check_rows(const Eigen::MatrixXd& data) const;
  Eigen::VectorXd x_min_, x_max_;
  // y = (x - offset) gain + y_min; constant features: gain 1, offset y_min.
  Eigen::VectorXd gain_, offset_;
  std::vector<Eigen::Index> constant_;
};

}  // namespace cnclab
