#include "cnclab/nn/metrics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

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

// Per split by hand. Test outputs 0.2, 0.5 against scaled targets 0.1, 0.9 ->
// normalised MSE (0.01 + 0.16) / 2; validation 0.3, 0.3, 0.6 against 0.3,
// 0.5, 0.3 -> (0 + 0.04 + 0.09) / 3. Physical metrics come from the physical
// matrices of their own split: test errors 0, 3; train errors 1, -1, 2.
TEST(Metrics, EachSplitByHand) {
  std::map<std::string, SplitData> d;
  SplitData& test = d["test"];
  test.predictions.resize(1, 2);
  test.predictions << 10, 20;
  test.targets.resize(1, 2);
  test.targets << 10, 23;
  test.outputs.resize(1, 2);
  test.outputs << 0.2, 0.5;
  test.scaled_targets.resize(1, 2);
  test.scaled_targets << 0.1, 0.9;
  SplitData& val = d["validation"];
  val.outputs.resize(1, 3);
  val.outputs << 0.3, 0.3, 0.6;
  val.scaled_targets.resize(1, 3);
  val.scaled_targets << 0.3, 0.5, 0.3;
  val.predictions = val.targets = Eigen::MatrixXd::Zero(1, 3);
  SplitData& train = d["train"];
  train.predictions.resize(1, 3);
  train.predictions << 1, 1, 5;
  train.targets.resize(1, 3);
  train.targets << 0, 2, 3;
  train.outputs = train.scaled_targets = Eigen::MatrixXd::Zero(1, 3);
  const auto m =
      evaluation_metrics(d, {"test.normalised_mse", "validation.normalised_mse", "test.mse",
                             "test.max_abs_error", "train.mae", "train.rmse", "validation.mse"});
  EXPECT_NEAR(m.at("test.normalised_mse"), (0.01 + 0.16) / 2, 1e-15);
  EXPECT_NEAR(m.at("validation.normalised_mse"), (0.04 + 0.09) / 3, 1e-15);
  EXPECT_DOUBLE_EQ(m.at("test.mse"), 9.0 / 2);
  EXPECT_DOUBLE_EQ(m.at("test.max_abs_error"), 3.0);
  EXPECT_DOUBLE_EQ(m.at("train.mae"), 4.0 / 3);
  EXPECT_DOUBLE_EQ(m.at("train.rmse"), std::sqrt(6.0 / 3));
  EXPECT_DOUBLE_EQ(m.at("validation.mse"), 0.0);
  EXPECT_EQ(m.size(), 7u);

  // A split without samples (or not given) has no metrics: left out, not NaN.
  d["validation"] = SplitData{};
  d.erase("train");
  const auto none = evaluation_metrics(d, {"validation.rmse", "train.mse", "test.rmse"});
  EXPECT_EQ(none.size(), 1u);
  EXPECT_TRUE(none.contains("test.rmse"));
  EXPECT_THROW(evaluation_metrics(d, {"rmse"}), Error);             // no split
  EXPECT_THROW(evaluation_metrics(d, {"holdout.rmse"}), Error);     // no such split
  EXPECT_THROW(evaluation_metrics(d, {"validation_rmse"}), Error);  // not a name
}

TEST(Metrics, NamesSplitsAndBases) {
  EXPECT_EQ(metric_name("validation", "rmse"), "validation.rmse");
  EXPECT_EQ(metric_split("validation.rmse"), "validation");
  EXPECT_EQ(metric_base("validation.rmse"), "rmse");
  EXPECT_EQ(metric_split("test.normalised_mse"), "test");
  EXPECT_EQ(metric_split("rmse"), "");
  EXPECT_EQ(metric_base("rmse"), "rmse");
  // A dotted name whose first part is no split has none (job metrics: sweep.trials).
  EXPECT_EQ(metric_split("sweep.trials"), "");
  EXPECT_EQ(metric_base("sweep.trials"), "sweep.trials");
}

// `metrics:` entries: a base name is that metric on every split given, a
// split name that one only, the older normalised_validation_mse is
// validation.normalised_mse; each name once, in the order asked.
TEST(Metrics, SelectionExpandsToStoredNames) {
  const auto& splits = metric_splits();
  EXPECT_EQ(expand_metric_selection({"rmse"}, base_metrics(), splits),
            (std::vector<std::string>{"train.rmse", "validation.rmse", "test.rmse"}));
  EXPECT_EQ(expand_metric_selection({"test.r2", kOlderValidationMse, "validation.normalised_mse"},
                                    base_metrics(), splits),
            (std::vector<std::string>{"test.r2", "validation.normalised_mse"}));
  EXPECT_EQ(expand_metric_selection({"mse"}, base_metrics(), {"train", "test"}),
            (std::vector<std::string>{"train.mse", "test.mse"}));
  EXPECT_THROW(expand_metric_selection({"rmsee"}, base_metrics(), splits), Error);
  EXPECT_THROW(expand_metric_selection({"holdout.rmse"}, base_metrics(), splits), Error);
  // Another model's names (narx: its registered ones on the validation half).
  EXPECT_EQ(expand_metric_selection({"contour_rms"}, {"contour_rms", "stable"}, {"validation"}),
            (std::vector<std::string>{"validation.contour_rms"}));
  EXPECT_THROW(expand_metric_selection({"test.contour_rms"}, {"contour_rms"}, {"validation"}),
               Error);
  const auto names = metric_selection_names(base_metrics(), splits);
  EXPECT_EQ(names.size(), base_metrics().size() * 4 + 1);
  EXPECT_EQ(names.back(), kOlderValidationMse);
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

// Each metric its own unit (metrics.hpp's table).
TEST(Metrics, EachMetricHasItsOwnUnit) {
  const std::vector<std::string> um = {"µm"};
  EXPECT_EQ(metric_unit("mse", um), "µm²");
  EXPECT_EQ(metric_unit("rmse", um), "µm");
  EXPECT_EQ(metric_unit("mae", um), "µm");
  EXPECT_EQ(metric_unit("max_abs_error", um), "µm");
  EXPECT_EQ(metric_unit("r2", um), "1");
  EXPECT_EQ(metric_unit("normalised_mse", um), "scaled²");
  // The unit is the base's, on any split.
  EXPECT_EQ(metric_unit("validation.normalised_mse", um), "scaled²");
  EXPECT_EQ(metric_unit("train.mse", um), "µm²");
  EXPECT_EQ(metric_unit("test.rmse", um), "µm");
  EXPECT_EQ(metric_unit("test.r2", um), "1");
  EXPECT_EQ(metric_unit("mse", {"1"}), "1");
  // Pooled outputs of different units (seed 004's x, y, z in mm, a, c in rad).
  EXPECT_EQ(metric_unit("mse", {"mm", "mm", "rad"}), "(mm, rad)²");
  EXPECT_EQ(metric_unit("rmse", {"mm", "mm", "rad"}), "(mm, rad)");
  for (const auto& name :
       expand_metric_selection(base_metrics(), base_metrics(), metric_splits())) {
    EXPECT_FALSE(metric_unit(name, um).empty()) << name;
  }
  EXPECT_EQ(metric_unit("accuracy", um), "");
}

}  // namespace
}  // namespace cnclab
