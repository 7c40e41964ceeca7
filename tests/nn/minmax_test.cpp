#include "cnclab/nn/minmax.hpp"

#include <gtest/gtest.h>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr double kTol = 1e-12;

TEST(MinMax, MatlabMapminmaxExample) {
  // MATLAB's mapminmax documentation example x1 = [1 2 4; 1 1 1; 3 2 2; 0 0 0]:
  // row 1 -> [-1, -1/3, 1] (2 (x - 1) / 3 - 1), row 3 -> [1, -1, -1], rows 2
  // and 4 are constant and pass through unchanged (y = x, "no change occurs").
  Eigen::MatrixXd x(4, 3);
  x << 1, 2, 4, 1, 1, 1, 3, 2, 2, 0, 0, 0;
  MinMaxNormaliser m;
  m.fit(x);
  Eigen::MatrixXd expected(4, 3);
  expected << -1, -1.0 / 3.0, 1, 1, 1, 1, 1, -1, -1, 0, 0, 0;
  EXPECT_TRUE(m.transform(x).isApprox(expected, kTol)) << m.transform(x);
  EXPECT_EQ(m.constant_features(), (std::vector<Eigen::Index>{1, 3}));
  EXPECT_TRUE(m.inverse_transform(m.transform(x)).isApprox(x, kTol));
  // mapminmax('apply', x2, ps) with x2 = [5 2 3; ...]: row 1 -> [5/3, -1/3, 1/3]
  // (by hand: 2 (x - 1) / 3 - 1; not clipped).
  Eigen::MatrixXd x2(4, 3);
  x2 << 5, 2, 3, 1, 1, 1, 6, 7, 3, 0, 0, 0;
  const Eigen::MatrixXd y2 = m.transform(x2);
  EXPECT_NEAR(y2(0, 0), 5.0 / 3.0, kTol);
  EXPECT_NEAR(y2(0, 1), -1.0 / 3.0, kTol);
  EXPECT_NEAR(y2(0, 2), 1.0 / 3.0, kTol);
  EXPECT_NEAR(y2(2, 1), 2.0 * (7 - 2) / 1.0 - 1, kTol);  // x_min 2, x_max 3
}

TEST(MinMax, TrainingRangeMapsToMinusOneOne) {
  Eigen::MatrixXd x(2, 5);
  x << 3, -2, 7, 0.5, 1, 100, 250, 175, 101, 249;
  MinMaxNormaliser m;
  m.fit(x);
  const Eigen::MatrixXd y = m.transform(x);
  for (Eigen::Index i = 0; i < 2; ++i) {
    EXPECT_NEAR(y.row(i).minCoeff(), -1.0, kTol);
    EXPECT_NEAR(y.row(i).maxCoeff(), 1.0, kTol);
  }
  const MinMaxNormaliser stored(m.x_min(), m.x_max());
  EXPECT_TRUE(stored.transform(x).isApprox(y, kTol));
}

TEST(MinMax, RejectsNonFiniteEmptyAndBadRanges) {
  MinMaxNormaliser m;
  EXPECT_THROW(m.fit(Eigen::MatrixXd(2, 0)), Error);
  Eigen::MatrixXd x = Eigen::MatrixXd::Ones(2, 3);
  x(1, 2) = std::nan("");
  EXPECT_THROW(m.fit(x), Error);
  EXPECT_THROW(
      MinMaxNormaliser(Eigen::VectorXd::Constant(1, 2.0), Eigen::VectorXd::Constant(1, 1.0)),
      Error);
  m.fit(Eigen::MatrixXd::Ones(2, 3));
  EXPECT_THROW(m.transform(Eigen::MatrixXd::Ones(3, 3)), Error);
}

}  // namespace
}  // namespace cnclab
