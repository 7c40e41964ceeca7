#pragma once
// Machine-space error of predicted joint sets: each predicted (X, Y, Z, A, C)
// is taken through forward kinematics and compared with the pose the true
// joints give - the tool-tip displacement a machinist would measure, and the
// tool-axis angle error.
#include <Eigen/Core>
#include <vector>

#include "cnclab/kinematics/tttrr.hpp"

namespace cnclab {

struct PoseErrors {
  std::vector<double> position_mm;  // |P(predicted) - P(true)| per sample [mm]
  std::vector<double> axis_rad;     // angle between O(predicted) and O(true) [rad]
};

// predicted, truth: 5 x n, rows X, Y, Z [mm], A, C [rad]. Throws cnclab::Error
// on mismatched shapes.
PoseErrors pose_errors(const TttrrMachine& machine, const Eigen::MatrixXd& predicted,
                       const Eigen::MatrixXd& truth);

}  // namespace cnclab
