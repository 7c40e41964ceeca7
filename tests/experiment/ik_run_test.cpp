// A per-axis IK run through the runner: target selection, count split,
// min-max target scaling and the normalised test and validation MSEs recorded
// in the result and recomputed here from the dataset independently.
#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/data/dataset_file.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/nn/mlp.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

const char* kIkYaml = R"(name: ik_tiny
seed: 8
dataset: {generator: ik_samples, targets: [C], options: {values_per_input: 3}}
split: {train_count: 120, test_count: 60}
normalisation: {inputs: minmax, targets: minmax, target_range: [0.1, 0.9]}
model: {hidden: [5, 4], hidden_activation: sigmoid, output_activation: sigmoid}
trainer: {type: sgdm, learning_rate: 0.3, momentum: 0.5, epochs: 3}
metrics: [mse, normalised_mse, normalised_validation_mse]  # the older name still reads
)";

TEST(IkRun, OneAxisWithCountSplitAndMinMaxTargets) {
  testing::TempDir dir;
  RunOptions o;
  o.results_dir = dir / "results";
  o.datasets_dir = dir / "datasets";
  const RunOutcome outcome = run_experiment(parse_experiment(kIkYaml, "ik_tiny.yaml"), o);
  ASSERT_TRUE(outcome.ok) << outcome.message;
  const RunRecord r = read_result(outcome.result_file);
  EXPECT_EQ(r.target_names, std::vector<std::string>{"C"});
  EXPECT_EQ(r.target_units, std::vector<std::string>{"rad"});
  EXPECT_EQ(r.split.train.size(), 120u);
  EXPECT_EQ(r.split.test.size(), 60u);
  EXPECT_EQ(r.split.validation.size(), 243u - 180u);
  EXPECT_EQ(r.model.outputs, 1u);
  EXPECT_EQ(r.target_scaling.method, Scaling::minmax);
  EXPECT_EQ(r.input_scaling.method, Scaling::minmax);
  EXPECT_EQ(r.target_scaling.y_min, 0.1);
  EXPECT_EQ(r.target_scaling.y_max, 0.9);

  // The recorded min and max are those of C (row 4) over the training
  // samples of the dataset file.
  const Dataset d = read_dataset(r.dataset_file);
  double lo = 1e300, hi = -1e300;
  for (std::size_t j : r.split.train) {
    lo = std::min(lo, d.targets(4, static_cast<Eigen::Index>(j)));
    hi = std::max(hi, d.targets(4, static_cast<Eigen::Index>(j)));
  }
  ASSERT_EQ(r.target_scaling.min.size(), 1);
  EXPECT_EQ(r.target_scaling.min[0], lo);
  EXPECT_EQ(r.target_scaling.max[0], hi);
  // Test targets are C of the test samples, in rad.
  for (std::size_t k = 0; k < r.split.test.size(); ++k) {
    ASSERT_EQ(r.test_targets(0, static_cast<Eigen::Index>(k)),
              d.targets(4, static_cast<Eigen::Index>(r.split.test[k])));
  }
  // The recorded scaling maps the training extremes to the range ends.
  Eigen::MatrixXd ends(1, 2);
  ends << lo, hi;
  const Eigen::MatrixXd mapped = r.target_scaling.transform(ends);
  EXPECT_NEAR(mapped(0, 0), 0.1, 1e-12);
  EXPECT_NEAR(mapped(0, 1), 0.9, 1e-12);

  // The normalised MSEs the runner records, recomputed from the dataset
  // file, the split, the recorded scalings and the stored network parameters.
  const Mlp mlp(r.model);
  const auto mse_over = [&](const std::vector<std::size_t>& idx) {
    Eigen::MatrixXd x(d.inputs.rows(), static_cast<Eigen::Index>(idx.size()));
    Eigen::MatrixXd y(1, static_cast<Eigen::Index>(idx.size()));
    for (std::size_t k = 0; k < idx.size(); ++k) {
      x.col(static_cast<Eigen::Index>(k)) = d.inputs.col(static_cast<Eigen::Index>(idx[k]));
      y(0, static_cast<Eigen::Index>(k)) = d.targets(4, static_cast<Eigen::Index>(idx[k]));
    }
    const Eigen::MatrixXd out = mlp.predict(r.parameters, r.input_scaling.transform(x));
    const Eigen::MatrixXd scaled = r.target_scaling.transform(y);
    double sum = 0;
    for (Eigen::Index k = 0; k < out.cols(); ++k) sum += std::pow(out(0, k) - scaled(0, k), 2);
    return sum / static_cast<double>(out.cols());
  };
  ASSERT_EQ(r.split.validation.size(), 63u);
  EXPECT_NEAR(r.metrics.at("validation.normalised_mse"), mse_over(r.split.validation), 1e-14);
  EXPECT_NEAR(r.metrics.at("test.normalised_mse"), mse_over(r.split.test), 1e-14);
  // Not the physical MSE (C in rad has another scale).
  EXPECT_GT(std::abs(r.metrics.at("test.normalised_mse") - r.metrics.at("test.mse")), 1e-6);
}

TEST(IkRun, UnknownTargetIsAConfigError) {
  testing::TempDir dir;
  RunOptions o;
  o.results_dir = dir / "results";
  o.datasets_dir = dir / "datasets";
  const auto loaded = parse_experiment(kIkYaml, "ik_tiny.yaml", {"dataset.targets=[B]"});
  EXPECT_THROW(run_experiment(loaded, o), ConfigError);
  EXPECT_FALSE(std::filesystem::exists(dir / "results"));
}

}  // namespace
}  // namespace cnclab
