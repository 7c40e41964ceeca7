#include "cnclab/kinematics/joint_error.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <string>

namespace cnclab {

PoseErrors pose_errors(const TttrrMachine& machine, const Eigen::MatrixXd& predicted,
                       const Eigen::MatrixXd& truth) {
  if (predicted.rows() != 5 || truth.rows() != 5 || predicted.cols() != truth.cols()) {
    throw Error("pose errors: need 5 x n joint matrices of equal size, got " +
                std::to_string(predicted.rows()) + "x" + std::to_string(predicted.cols()) +
                " and " + std::to_string(truth.rows()) + "x" + std::to_string(truth.cols()));
  }
  const auto joints = [](const Eigen::MatrixXd& m, Eigen::Index j) {
    return Joints{m(0, j), m(1, j), m(2, j), m(3, j), m(4, j)};
  };
  PoseErrors e;
  for (Eigen::Index j = 0; j < predicted.cols(); ++j) {
    const ToolPose p = machine.forward(joints(predicted, j));
    const ToolPose t = machine.forward(joints(truth, j));
    e.position_mm.push_back((p.position - t.position).norm());
    // atan2(|a x b|, a . b): accurate for small angles, unlike acos.
    e.axis_rad.push_back(
        std::atan2(p.orientation.cross(t.orientation).norm(), p.orientation.dot(t.orientation)));
  }
  return e;
}

}  // namespace cnclab
