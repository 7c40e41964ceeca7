#include "cnclab/nn/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

TEST(Metrics, HandComputedValues) {
  Eigen::MatrixXd y(1, 4), p(1, 4);
  y << 1, 2, 3, 4;
  p << 1, 3, 3, 2;  // errors 0, 1, 0, -2
  const auto m = regression_metrics(p, y, physical_metrics());
  EXPECT_DOUBLE_EQ(m.at("mse"), 5.0 / 4);
  EXPECT_DOUBLE_EQ(m.at("rmse"), std::sqrt(5.0 / 4));
  EXPECT_DOUBLE_EQ(m.at("mae"), 3.0 / 4);
  EXPECT_DOUBLE_EQ(m.at("max_abs_error"), 2.0);
  EXPECT_DOUBLE_EQ(m.at("r2"), 1.0 - 5.0 / 5.0);  // Σ(y-ȳ)² = 5
}

// Normalised MSEs by hand: test outputs 0.2, 0.5 against 0.1, 0.9 ->
// (0.01 + 0.16) / 2; validation 0.3, 0.3, 0.6 against 0.3, 0.5, 0.3 ->
// (0 + 0.04 + 0.09) / 3. Physical metrics come from the physical matrices.
TEST(Metrics, NormalisedTestAndValidationMseByHand) {
  EvaluationData d;
  d.test_predictions.resize(1, 2);
  d.test_predictions << 10, 20;
  d.test_targets.resize(1, 2);
  d.test_targets << 10, 23;
  d.test_outputs.resize(1, 2);
  d.test_outputs << 0.2, 0.5;
  d.test_scaled_targets.resize(1, 2);
  d.test_scaled_targets << 0.1, 0.9;
  d.validation_outputs.resize(1, 3);
  d.validation_outputs << 0.3, 0.3, 0.6;
  d.validation_scaled_targets.resize(1, 3);
  d.validation_scaled_targets << 0.3, 0.5, 0.3;
  const auto m = evaluation_metrics(d, known_metrics());
  EXPECT_NEAR(m.at("normalised_mse"), (0.01 + 0.16) / 2, 1e-15);
  EXPECT_NEAR(m.at("normalised_validation_mse"), (0.04 + 0.09) / 3, 1e-15);
  EXPECT_DOUBLE_EQ(m.at("mse"), 9.0 / 2);
  EXPECT_DOUBLE_EQ(m.at("max_abs_error"), 3.0);
  EXPECT_EQ(m.size(), known_metrics().size());

  // No validation split: NaN, not an error.
  d.validation_outputs.resize(1, 0);
  d.validation_scaled_targets.resize(1, 0);
  EXPECT_TRUE(std::isnan(
      evaluation_metrics(d, {"normalised_validation_mse"}).at("normalised_validation_mse")));
  EXPECT_THROW(evaluation_metrics(d, {"validation_rmse"}), Error);
}

TEST(Metrics, PerfectPredictionHasR2One) {
  Eigen::MatrixXd y = Eigen::MatrixXd::Random(2, 10);
  const auto m = regression_metrics(y, y, {"r2", "mse"});
  EXPECT_DOUBLE_EQ(m.at("r2"), 1.0);
  EXPECT_DOUBLE_EQ(m.at("mse"), 0.0);
}

// 21 values 0..20: rank 0.95 * 20 = 19 exactly -> 19; 11 values 0..10: rank
// 9.5 -> 9.5 (halfway between 9 and 10), as numpy.percentile(x, 95).
TEST(ErrorSummary, PercentileMeanMaxByHand) {
  std::vector<double> a;
  for (int i = 20; i >= 0; --i) a.push_back(i);
  const ErrorSummary s = summarize_errors(a);
  EXPECT_EQ(s.count, 21u);
  EXPECT_DOUBLE_EQ(s.mean, 10.0);
  EXPECT_DOUBLE_EQ(s.p95, 19.0);
  EXPECT_DOUBLE_EQ(s.max, 20.0);
  std::vector<double> b;
  for (int i = 0; i <= 10; ++i) b.push_back(i);
  EXPECT_DOUBLE_EQ(summarize_errors(b).p95, 9.5);
  EXPECT_DOUBLE_EQ(summarize_errors({3.0}).p95, 3.0);
  EXPECT_TRUE(std::isnan(summarize_errors({}).mean));
  EXPECT_THROW(summarize_errors({1.0, std::nan("")}), Error);
}

// Issue 22 item 5: each metric its own unit (metrics.hpp's table).
TEST(Metrics, EachMetricHasItsOwnUnit) {
  const std::vector<std::string> um = {"µm"};
  EXPECT_EQ(metric_unit("mse", um), "µm²");
  EXPECT_EQ(metric_unit("rmse", um), "µm");
  EXPECT_EQ(metric_unit("mae", um), "µm");
  EXPECT_EQ(metric_unit("max_abs_error", um), "µm");
  EXPECT_EQ(metric_unit("r2", um), "1");
  EXPECT_EQ(metric_unit("normalised_mse", um), "scaled²");
  EXPECT_EQ(metric_unit("normalised_validation_mse", um), "scaled²");
  EXPECT_EQ(metric_unit("mse", {"1"}), "1");
  // Pooled outputs of different units (seed 004's x, y, z in mm, a, c in rad).
  EXPECT_EQ(metric_unit("mse", {"mm", "mm", "rad"}), "(mm, rad)²");
  EXPECT_EQ(metric_unit("rmse", {"mm", "mm", "rad"}), "(mm, rad)");
  for (const auto& name : known_metrics()) EXPECT_FALSE(metric_unit(name, um).empty()) << name;
  EXPECT_EQ(metric_unit("accuracy", um), "");
}

}  // namespace
}  // namespace cnclab
