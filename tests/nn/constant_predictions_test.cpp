// The degenerate-network rule (constant_predictions.hpp) on hand-made
// vectors: variances worked out by hand against the 1e-6 ratio.
#include "cnclab/nn/constant_predictions.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

using Rows = std::vector<Eigen::Index>;

Eigen::MatrixXd row(std::initializer_list<double> v) {
  Eigen::MatrixXd m(1, static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double x : v) m(0, i++) = x;
  return m;
}

// Targets 1, 2, 3, 4: mean 2.5, population variance (2.25 + 0.25) · 2 / 4 = 1.25,
// so the threshold is 1.25e-6.
const Eigen::MatrixXd kTargets = row({1, 2, 3, 4});

TEST(ConstantPredictions, ConstantOutputIsFlagged) {
  EXPECT_EQ(constant_prediction_rows(row({5.8295, 5.8295, 5.8295, 5.8295}), kTargets), Rows{0});
}

TEST(ConstantPredictions, VarianceBelowTheRatioIsFlaggedAboveIsNot) {
  // 2.5 ± a alternating: population variance a².
  // a = 1e-3: 1e-6 < 1.25e-6, flagged; a = 1.2e-3: 1.44e-6 > 1.25e-6, not.
  EXPECT_EQ(constant_prediction_rows(row({2.501, 2.499, 2.501, 2.499}), kTargets), Rows{0});
  EXPECT_TRUE(constant_prediction_rows(row({2.5012, 2.4988, 2.5012, 2.4988}), kTargets).empty());
  // Far below: 1e-8.
  EXPECT_EQ(constant_prediction_rows(row({3.0001, 2.9999, 3.0001, 2.9999}), kTargets), Rows{0});
}

TEST(ConstantPredictions, OrdinaryPredictionsAreNotFlagged) {
  EXPECT_TRUE(constant_prediction_rows(row({1.1, 1.9, 3.2, 3.8}), kTargets).empty());
  // A bad but varying fit (r2 < 0) is not degenerate either.
  EXPECT_TRUE(constant_prediction_rows(row({4, 3, 2, 1}), kTargets).empty());
}

TEST(ConstantPredictions, ConstantTargets) {
  const Eigen::MatrixXd flat = row({2, 2, 2});
  EXPECT_EQ(constant_prediction_rows(row({2, 2, 2}), flat), Rows{0});  // constant: flagged
  EXPECT_TRUE(constant_prediction_rows(row({1, 2, 3}), flat).empty());
}

TEST(ConstantPredictions, OnlyTheDegenerateOutputRowIsReported) {
  Eigen::MatrixXd y(2, 4), p(2, 4);
  y << 1, 2, 3, 4, 10, 20, 30, 40;
  p << 1.1, 1.9, 3.2, 3.8, 25, 25, 25, 25;
  EXPECT_EQ(constant_prediction_rows(p, y), Rows{1});
}

TEST(ConstantPredictions, TooFewSamplesOrNaNAreNotFlagged) {
  EXPECT_TRUE(constant_prediction_rows(row({3}), row({1})).empty());
  EXPECT_TRUE(constant_prediction_rows(Eigen::MatrixXd(1, 0), Eigen::MatrixXd(1, 0)).empty());
  EXPECT_TRUE(constant_prediction_rows(row({std::nan(""), 1, 1, 1}), kTargets).empty());
}

TEST(ConstantPredictions, MismatchedShapesAreAnError) {
  EXPECT_THROW(constant_prediction_rows(row({1, 2}), kTargets), Error);
}

}  // namespace
}  // namespace cnclab
