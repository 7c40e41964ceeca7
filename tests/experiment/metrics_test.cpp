#include "cnclab/experiment/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace cnclab {
namespace {

TEST(Metrics, HandComputedValues) {
  Eigen::MatrixXd y(1, 4), p(1, 4);
  y << 1, 2, 3, 4;
  p << 1, 3, 3, 2;  // errors 0, 1, 0, -2
  const auto m = regression_metrics(p, y, known_metrics());
  EXPECT_DOUBLE_EQ(m.at("mse"), 5.0 / 4);
  EXPECT_DOUBLE_EQ(m.at("rmse"), std::sqrt(5.0 / 4));
  EXPECT_DOUBLE_EQ(m.at("mae"), 3.0 / 4);
  EXPECT_DOUBLE_EQ(m.at("max_abs_error"), 2.0);
  EXPECT_DOUBLE_EQ(m.at("r2"), 1.0 - 5.0 / 5.0);  // Σ(y-ȳ)² = 5
}

TEST(Metrics, PerfectPredictionHasR2One) {
  Eigen::MatrixXd y = Eigen::MatrixXd::Random(2, 10);
  const auto m = regression_metrics(y, y, {"r2", "mse"});
  EXPECT_DOUBLE_EQ(m.at("r2"), 1.0);
  EXPECT_DOUBLE_EQ(m.at("mse"), 0.0);
}

}  // namespace
}  // namespace cnclab
