#include "cnclab/kinematics/joint_error.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/core/rng.hpp"

namespace cnclab {
namespace {

// Closed forms: forward kinematics is a rigid motion of the table, so an
// error dX alone moves the tool tip by |dX|; with C fixed, an error dA alone
// turns the tool axis O = (sA sC, sA cC, cA) by |dA|.
TEST(PoseErrors, LinearAndTiltErrorsByHand) {
  const TttrrMachine m(TttrrOptions{});
  Rng rng(3);
  Eigen::MatrixXd truth(5, 200);
  for (Eigen::Index j = 0; j < truth.cols(); ++j) {
    truth.col(j) << rng.uniform(-50, 50), rng.uniform(-50, 50), rng.uniform(-50, 50),
        rng.uniform(0.1, 1.0), rng.uniform(-3, 3);
  }
  Eigen::MatrixXd dx = truth;
  dx.row(0).array() += 0.25;
  const PoseErrors ex = pose_errors(m, dx, truth);
  for (std::size_t j = 0; j < ex.position_mm.size(); ++j) {
    ASSERT_NEAR(ex.position_mm[j], 0.25, 1e-12);
    ASSERT_NEAR(ex.axis_rad[j], 0.0, 1e-15);
  }
  Eigen::MatrixXd da = truth;
  da.row(3).array() += 1e-3;
  const PoseErrors ea = pose_errors(m, da, truth);
  for (double a : ea.axis_rad) ASSERT_NEAR(a, 1e-3, 1e-12);
  EXPECT_THROW(pose_errors(m, truth.topRows(4), truth), Error);
}

}  // namespace
}  // namespace cnclab
