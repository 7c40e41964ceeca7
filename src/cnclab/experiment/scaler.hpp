#pragma once
// The normaliser an experiment's `normalisation:` names, fitted on training
// data, as one value: z-score (nn/zscore.hpp), min-max (nn/minmax.hpp) or
// none (identity). Recorded in and restored from result files.
#include <Eigen/Core>
#include <array>
#include <optional>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/nn/minmax.hpp"
#include "cnclab/nn/zscore.hpp"

namespace cnclab {

class FeatureScaler {
 public:
  // Fits `kind` on `data` (features x samples); range is used by minmax.
  static FeatureScaler fit(Scaling kind, const std::array<double, 2>& range,
                           const Eigen::MatrixXd& data);
  // The normaliser a result file recorded (throws cnclab::Error if invalid).
  static FeatureScaler from_record(const ScalingRecord& record);

  Eigen::MatrixXd transform(const Eigen::MatrixXd& data) const;
  Eigen::MatrixXd inverse_transform(const Eigen::MatrixXd& scaled) const;
  ScalingRecord record() const;

 private:
  std::optional<ZScoreNormaliser> zscore_;
  std::optional<MinMaxNormaliser> minmax_;
};

}  // namespace cnclab
