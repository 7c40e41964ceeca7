#include "cnclab/nn/minmax.hpp"

#include <gtest/gtest.h>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr double kTol = 1e-12;

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

TEST(MinMax, DefaultRangeIsMapminmaxsMinusOneToOne) {
  Eigen::MatrixXd x(1, 2);
  x << 10, 30;
  MinMaxNormaliser n;
  n.fit(x);
  Eigen::MatrixXd probe(1, 3);
  probe << 10, 20, 40;  // 40 lies outside the training range: extrapolates linearly
  const Eigen::MatrixXd y = n.transform(probe);
  EXPECT_NEAR(y(0, 0), -1.0, kTol);
  EXPECT_NEAR(y(0, 1), 0.0, kTol);
  EXPECT_NEAR(y(0, 2), 2.0, kTol);
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

TEST(MinMax, BadInputIsAnError) {
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
