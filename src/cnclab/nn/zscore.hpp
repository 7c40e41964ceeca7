#pragma once
// Z-score normalisation (seed 000 Eq. 7): x' = (x - mu) / S per feature, with
// mu the mean and S the sample standard deviation (n - 1) of the TRAINING
// split. A constant feature (S = 0) gets S = 1, so it maps to 0 instead of
// dividing by zero; constant_features() lists them.
#include <Eigen/Core>
#include <vector>

namespace cnclab {

class ZScoreNormaliser {
 public:
  ZScoreNormaliser() = default;
  ZScoreNormaliser(Eigen::VectorXd mean, Eigen::VectorXd std);

  // data: features x samples, >= 2 samples, all finite (else cnclab::Error).
  void fit(const Eigen::MatrixXd& data);
  Eigen::MatrixXd transform(const Eigen::MatrixXd& data) const;
  Eigen::MatrixXd inverse_transform(const Eigen::MatrixXd& scaled) const;

  const Eigen::VectorXd& mean() const { return mean_; }
  const Eigen::VectorXd& std() const { return std_; }
  const std::vector<Eigen::Index>& constant_features() const { return constant_; }

 private:
  void check_rows(const Eigen::MatrixXd& data) const;
  Eigen::VectorXd mean_, std_;
  std::vector<Eigen::Index> constant_;
};

}  // namespace cnclab
