#pragma once
// Per-feature normalisation of an experiment's inputs or targets, fitted on
// the training split only: z-score (seed 000 Eq. 7; nn/zscore.hpp), min-max
// to a range [y_min, y_max] (MATLAB mapminmax, default [-1, 1];
// nn/minmax.hpp), or none. ScalingRecord is what a result file stores to
// undo it.
#include <Eigen/Core>
#include <array>
#include <string>

#include "cnclab/nn/minmax.hpp"

namespace cnclab {

enum class Scaling { zscore, minmax, none };
std::string to_string(Scaling s);
// False if `text` names no scaling.
bool parse_scaling(const std::string& text, Scaling& s);

struct ScalingRecord {
  Scaling method = Scaling::none;
  Eigen::VectorXd mean, std;  // zscore: per-feature mean and sample std (n - 1)
  Eigen::VectorXd min, max;   // minmax: per-feature training range
  double y_min = MinMaxNormaliser::kYMin, y_max = MinMaxNormaliser::kYMax;  // minmax: range

  // Fits `method` on `train` (features x samples); `range` = [y_min, y_max]
  // of minmax.
  static ScalingRecord fit(Scaling method, const Eigen::MatrixXd& train,
                           const std::array<double, 2>& range = {MinMaxNormaliser::kYMin,
                                                                 MinMaxNormaliser::kYMax});
  Eigen::MatrixXd transform(const Eigen::MatrixXd& data) const;
  Eigen::MatrixXd inverse_transform(const Eigen::MatrixXd& scaled) const;

 private:
  template <class Map>
  Eigen::MatrixXd apply(const Eigen::MatrixXd& data, Map map) const;
};

}  // namespace cnclab
