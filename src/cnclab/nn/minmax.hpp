#pragma once
// Min-max normalisation to a configurable range [low, high] per feature, as
// MATLAB's mapminmax (default range [-1, 1]):
//   x' = low + (high - low) (x - min) / (max - min),
// with min and max of the TRAINING split. A sigmoid output layer needs a
// range inside (0, 1), e.g. [0.1, 0.9] (seed 004's networks). A constant
// feature (max = min) maps to low, as mapminmax does; constant_features()
// lists them.
#include <Eigen/Core>
#include <vector>

namespace cnclab {

class MinMaxNormaliser {
 public:
  // low < high, both finite (else cnclab::Error).
  explicit MinMaxNormaliser(double low = -1.0, double high = 1.0);
  // Restores a fitted normaliser; min and max of equal size, finite, min <= max.
  MinMaxNormaliser(Eigen::VectorXd min, Eigen::VectorXd max, double low, double high);

  // data: features x samples, >= 1 sample, all finite (else cnclab::Error).
  void fit(const Eigen::MatrixXd& data);
  Eigen::MatrixXd transform(const Eigen::MatrixXd& data) const;
  Eigen::MatrixXd inverse_transform(const Eigen::MatrixXd& scaled) const;

  const Eigen::VectorXd& min() const { return min_; }
  const Eigen::VectorXd& max() const { return max_; }
  double low() const { return low_; }
  double high() const { return high_; }
  const std::vector<Eigen::Index>& constant_features() const { return constant_; }

 private:
  void check_rows(const Eigen::MatrixXd& data) const;
  void set_gain();
  double low_ = -1.0, high_ = 1.0;
  Eigen::VectorXd min_, max_, gain_;  // gain = (high - low) / (max - min), 0 for constant
  std::vector<Eigen::Index> constant_;
};

}  // namespace cnclab
