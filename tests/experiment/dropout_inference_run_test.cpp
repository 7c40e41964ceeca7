// A run of a network with dropout is evaluated both ways from one training
// (model.dropout.inference, nn/mlp.hpp): the result holds its reported
// evaluation and the other one; MC dropout's masks come from the run's own
// stream "mc_dropout" (derived from the experiment seed), checked by
// recomputing the stored MC test predictions from the stored network, the
// dataset file and the split; the inference is part of the result's
// identity, and choosing the other one swaps the two evaluations of the same
// trained network.
#include <gtest/gtest.h>

#include <string>

#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_inference.hpp"
#include "cnclab/experiment/runner.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

std::string tiny_yaml(const std::string& dropout) {
  return "name: tiny_dropout\nseed: 5\n"
         "dataset: {generator: friedman1, options: {samples: 300, inputs: 6, noise_std: 0.5}}\n"
         "normalisation: {inputs: zscore, targets: zscore}\n"
         "model: {hidden: [16, 12], hidden_activation: tanh, init: {weights: {type: xavier}}, "
         "dropout: " +
         dropout +
         "}\n"
         "trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 16, epochs: 15}\n";
}

RunRecord run(const TempDir& dir, const std::string& dropout) {
  RunOptions o;
  o.results_dir = dir / "results";
  o.datasets_dir = dir / "datasets";
  const RunOutcome outcome = run_experiment(parse_experiment(tiny_yaml(dropout), "tiny.yaml"), o);
  EXPECT_TRUE(outcome.ok) << outcome.message;
  return read_result(outcome.result_file);
}

TEST(DropoutInferenceRun, OneTrainingEvaluatedBothWaysFromItsOwnStream) {
  TempDir dir;
  const RunRecord r = run(dir, "{keep_probability: 0.6, mc_samples: 40}");
  // The default inference leaves the key out of the identity (results made
  // before it existed keep theirs); a non-default count is in it.
  EXPECT_EQ(r.resolved_yaml.find("inference"), std::string::npos) << r.resolved_yaml;
  EXPECT_NE(r.resolved_yaml.find("mc_samples: 40"), std::string::npos) << r.resolved_yaml;
  EXPECT_EQ(r.model.dropout_inference, DropoutInference::deterministic);
  EXPECT_EQ(r.model.dropout_mc_samples, 40u);
  ASSERT_TRUE(r.other_inference.has_value());
  EXPECT_EQ(r.other_inference->inference, DropoutInference::mc);
  // Every split evaluated both ways, under the same "<split>.<base>" names.
  ASSERT_EQ(r.other_inference->metrics.size(), r.metrics.size());
  for (const auto& [name, value] : r.metrics) {
    EXPECT_EQ(r.other_inference->metrics.count(name), 1u) << name;
  }
  EXPECT_EQ(r.metrics.count("train.mse"), 1u);

  // The MC predictions again, from what the result names: the dataset file,
  // the test split, the scalings and the parameters; masks from the stream
  // "test" under "mc_dropout" of the experiment seed.
  const Dataset data = read_dataset(r.dataset_file);
  Eigen::MatrixXd x(data.inputs.rows(), static_cast<Eigen::Index>(r.split.test.size()));
  for (std::size_t j = 0; j < r.split.test.size(); ++j) {
    x.col(static_cast<Eigen::Index>(j)) =
        data.inputs.col(static_cast<Eigen::Index>(r.split.test[j]));
  }
  Rng rng(derive_seed(derive_seed(5, "mc_dropout"), "test"));
  const Eigen::MatrixXd mc = r.target_scaling.inverse_transform(
      Mlp(r.model).predict_mc(r.parameters, r.input_scaling.transform(x), 40, rng));
  const Eigen::MatrixXd* stored = test_predictions_by(r, DropoutInference::mc);
  ASSERT_NE(stored, nullptr);
  EXPECT_LT((*stored - mc).cwiseAbs().maxCoeff(), 1e-12);
  // The MC test metric is that of those predictions (physical units).
  EXPECT_NEAR(r.other_inference->metrics.at("test.mse"),
              (mc - r.test_targets).array().square().mean(), 1e-9);
  EXPECT_EQ(test_predictions_by(r, DropoutInference::deterministic), &r.test_predictions);
  EXPECT_GT((*stored - r.test_predictions).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(r.provenance.derived_seeds.at("mc_dropout"), derive_seed(5, "mc_dropout"));

  // inference mc: another result (identity), the same trained network, the
  // two evaluations swapped.
  const RunRecord m = run(dir, "{keep_probability: 0.6, mc_samples: 40, inference: mc}");
  EXPECT_NE(m.config_hash, r.config_hash);
  EXPECT_EQ(m.parameters, r.parameters);
  ASSERT_TRUE(m.other_inference.has_value());
  EXPECT_EQ(m.other_inference->inference, DropoutInference::deterministic);
  EXPECT_EQ(m.metrics, r.other_inference->metrics);
  EXPECT_EQ(m.other_inference->metrics, r.metrics);
  EXPECT_EQ(m.test_predictions, *stored);
}

TEST(DropoutInferenceRun, WithoutDropoutThereIsOneEvaluation) {
  TempDir dir;
  const RunRecord r = run(dir, "{keep_probability: 1.0, inference: mc}");
  EXPECT_FALSE(r.other_inference.has_value());
  EXPECT_EQ(test_predictions_by(r, DropoutInference::deterministic), &r.test_predictions);
  EXPECT_EQ(test_predictions_by(r, DropoutInference::mc), &r.test_predictions);
}

}  // namespace
}  // namespace cnclab
