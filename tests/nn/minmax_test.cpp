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

// A range other than mapminmax's default (seed 004's sigmoid outputs).
// Hand-computed: feature 0 spans [2, 6], feature 1 [-1, 1]; range [0.1, 0.9]
// maps x to 0.1 + 0.8 (x - min) / (max - min).
TEST(MinMax, MapsTrainingExtremesToTheRangeEnds) {
  Eigen::MatrixXd x(2, 3);
  x << 2, 4, 6,  //
      -1, 1, 0;
  MinMaxNormaliser n(0.1, 0.9);
  n.fit(x);
  const Eigen::MatrixXd y = n.transform(x);
  Eigen::MatrixXd expected(2, 3);
  expected << 0.1, 0.5, 0.9,  //
      0.1, 0.9, 0.5;
  EXPECT_LT((y - expected).cwiseAbs().maxCoeff(), kTol);
  EXPECT_LT((n.inverse_transform(y) - x).cwiseAbs().maxCoeff(), kTol);
  EXPECT_EQ(n.x_min()(0), 2.0);
  EXPECT_EQ(n.x_max()(1), 1.0);
}

// MATLAB mapminmax: a constant row passes through unchanged (y = x).
TEST(MinMax, ConstantFeaturePassesThrough) {
  Eigen::MatrixXd x(2, 3);
  x << 5, 5, 5,  //
      0, 1, 2;
  MinMaxNormaliser n(0.1, 0.9);
  n.fit(x);
  EXPECT_EQ(n.constant_features(), std::vector<Eigen::Index>{0});
  Eigen::MatrixXd probe(2, 1);
  probe << 7, 1;
  const Eigen::MatrixXd y = n.transform(probe);
  EXPECT_NEAR(y(0, 0), 7.0, kTol);
  EXPECT_NEAR(y(1, 0), 0.5, kTol);
  EXPECT_LT((n.inverse_transform(y) - probe).cwiseAbs().maxCoeff(), kTol);
}

TEST(MinMax, RestoredEqualsFitted) {
  Eigen::MatrixXd x(2, 4);
  x << 1, 2, 3, 7, -4, 0, 2, 9;
  MinMaxNormaliser fitted(0.1, 0.9);
  fitted.fit(x);
  const MinMaxNormaliser restored(fitted.x_min(), fitted.x_max(), 0.1, 0.9);
  EXPECT_LT((restored.transform(x) - fitted.transform(x)).cwiseAbs().maxCoeff(), kTol);
}

TEST(MinMax, RejectsBadRangeAndRestoredRanges) {
  EXPECT_THROW(MinMaxNormaliser(1.0, 1.0), Error);
  EXPECT_THROW(MinMaxNormaliser(0.0, std::nan("")), Error);
  MinMaxNormaliser n;
  EXPECT_THROW(n.fit(Eigen::MatrixXd(2, 0)), Error);
  Eigen::MatrixXd bad(1, 2);
  bad << 1, std::nan("");
  EXPECT_THROW(n.fit(bad), Error);
  Eigen::MatrixXd ok(1, 2);
  ok << 1, 2;
  n.fit(ok);
  EXPECT_THROW(n.transform(Eigen::MatrixXd(3, 1)), Error);
  EXPECT_THROW(
      MinMaxNormaliser(Eigen::VectorXd::Constant(1, 2.0), Eigen::VectorXd::Constant(1, 1.0), 0, 1),
      Error);
}

}  // namespace
}  // namespace cnclab
