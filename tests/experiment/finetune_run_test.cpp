// Fine-tuning through init_from, as seed 000's transfer stages use it: the
// normaliser kept from the upstream result or refitted, evaluation-only runs
// (trainer.epochs 0 on an empty training part), and the subset sizes of
// seed 000 Tables 4 and 5.
#include <gtest/gtest.h>

#include <fstream>

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// A small upstream network and a downstream experiment on another sample of
// the same function (other generator seed: other inputs, other statistics).
const char* kUpstream = R"(name: up
seed: 5
dataset: {generator: friedman1, options: {samples: 200, inputs: 6, noise_std: 0.5}}
model: {hidden: [8], hidden_activation: tanh, init: {weights: {type: xavier}}}
trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 10, epochs: 20}
)";

std::string downstream(const std::string& extra, int epochs = 5) {
  return "name: down\nseed: 6\n"
         "dataset: {generator: friedman1, seed: 99, options: {samples: 300, inputs: 6}}\n"
         "model: {hidden: [8], hidden_activation: tanh}\n"
         "trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 10, epochs: " +
         std::to_string(epochs) + "}\n" + extra;
}

struct Fixture {
  TempDir dir;
  RunOptions options;
  RunRecord upstream;

  Fixture() {
    options.results_dir = dir / "results";
    options.datasets_dir = dir / "datasets";
    std::ofstream(dir / "up.yaml") << kUpstream;
    const RunOutcome up = run_experiment(load_experiment(dir / "up.yaml"), options);
    EXPECT_TRUE(up.ok) << up.message;
    upstream = read_result(up.result_file);
  }
  RunRecord run(const std::string& yaml) {
    std::ofstream(dir / "down.yaml") << yaml;
    const RunOutcome out = run_experiment(load_experiment(dir / "down.yaml"), options);
    EXPECT_TRUE(out.ok) << out.message;
    return read_result(out.result_file);
  }
};

void expect_identical(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  ASSERT_EQ(a.size(), b.size());
  for (Eigen::Index i = 0; i < a.size(); ++i) EXPECT_EQ(a[i], b[i]) << "entry " << i;
}

TEST(FineTune, KeepReusesTheUpstreamScalingExactlyAndRefitFitsTheNewTrainingSplit) {
  Fixture f;
  const RunRecord keep = f.run(downstream("init_from: {experiment: up.yaml, normaliser: keep}\n"));
  expect_identical(keep.input_scaling.mean, f.upstream.input_scaling.mean);
  expect_identical(keep.input_scaling.std, f.upstream.input_scaling.std);
  expect_identical(keep.target_scaling.mean, f.upstream.target_scaling.mean);
  expect_identical(keep.target_scaling.std, f.upstream.target_scaling.std);

  // refit (the default): Eq. 7 on this run's own training columns, which
  // differ from the upstream's statistics.
  const RunRecord refit = f.run(downstream("init_from: {experiment: up.yaml}\n"));
  const Dataset data = read_dataset(refit.dataset_file);
  Eigen::MatrixXd y_train(1, static_cast<Eigen::Index>(refit.split.train.size()));
  for (std::size_t j = 0; j < refit.split.train.size(); ++j)
    y_train(0, static_cast<Eigen::Index>(j)) =
        data.targets(0, static_cast<Eigen::Index>(refit.split.train[j]));
  const double mean = y_train.mean();
  const double var = (y_train.array() - mean).square().sum() / (y_train.cols() - 1.0);
  EXPECT_NEAR(refit.target_scaling.mean[0], mean, 1e-12 * std::abs(mean));
  EXPECT_NEAR(refit.target_scaling.std[0], std::sqrt(var), 1e-12 * std::sqrt(var));
  EXPECT_NE(refit.target_scaling.mean[0], f.upstream.target_scaling.mean[0]);
  EXPECT_NE(refit.resolved_yaml, keep.resolved_yaml);
  EXPECT_NE(keep.resolved_yaml.find("normaliser: keep"), std::string::npos);
}

TEST(FineTune, EvaluationOnlyRunKeepsTheUpstreamParametersBitForBitAndTestsOnAllSamples) {
  Fixture f;
  const RunRecord eval = f.run(
      downstream("init_from: {experiment: up.yaml, normaliser: keep}\nsplit: {train: 0}\n", 0));
  expect_identical(eval.parameters, f.upstream.parameters);
  EXPECT_TRUE(eval.split.train.empty());
  EXPECT_EQ(eval.split.test.size(), 300u);
  EXPECT_EQ(eval.test_predictions.cols(), 300);
  EXPECT_TRUE(eval.test_loss.empty());  // no epochs
  EXPECT_EQ(eval.training.termination, Termination::max_epochs);
  // The predictions are the upstream network's through the upstream
  // normaliser: an independent forward pass gives the same numbers.
  const Dataset data = read_dataset(eval.dataset_file);
  const Mlp mlp(f.upstream.model);
  const Eigen::MatrixXd pred = f.upstream.target_scaling.inverse_transform(
      mlp.predict(f.upstream.parameters, f.upstream.input_scaling.transform(data.inputs)));
  ASSERT_EQ(pred.cols(), eval.test_predictions.cols());
  EXPECT_LT((pred - eval.test_predictions).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(FineTune, ConfigurationsThatCannotWorkAreErrorsNamingTheKey) {
  Fixture f;
  const auto error_of = [&](const std::string& yaml) -> std::string {
    std::ofstream(f.dir / "bad.yaml") << yaml;
    try {
      run_experiment(load_experiment(f.dir / "bad.yaml"), f.options);
    } catch (const ConfigError& e) {
      return e.what();
    }
    return "";
  };
  // Training on no samples.
  EXPECT_NE(error_of(downstream("init_from: {experiment: up.yaml, normaliser: keep}\n"
                                "split: {train: 0}\n"))
                .find("split.train = 0: leaves 0 training samples"),
            std::string::npos);
  // Refitting on no samples.
  EXPECT_NE(error_of(downstream("init_from: {experiment: up.yaml}\nsplit: {train_count: 0}\n", 0))
                .find("split.train_count = 0: leaves no training samples to fit the normaliser"),
            std::string::npos);
  EXPECT_NE(error_of(downstream("init_from: {experiment: up.yaml, normaliser: kept}\n"))
                .find("init_from.normaliser = kept: must be one of: refit, keep"),
            std::string::npos);
  // Keeping a z-score normaliser while asking for min-max.
  EXPECT_NE(error_of(downstream("init_from: {experiment: up.yaml, normaliser: keep}\n"
                                "normalisation: {inputs: minmax}\n"))
                .find("scaled its inputs with zscore but normalisation.inputs is minmax"),
            std::string::npos);
}

// Seed 000 Tables 4 and 5: 0, 1, 5, 10, 15 % of 19,800 samples for training
// leave test sets of 19,800 / 19,602 / 18,810 / 17,820 / 16,830.
TEST(FineTune, SubsetSharesGiveTheTestSizesOfSeed000Tables4And5) {
  const double share[] = {0.0, 0.01, 0.05, 0.10, 0.15};
  const std::size_t test[] = {19800, 19602, 18810, 17820, 16830};
  for (int i = 0; i < 5; ++i) {
    SplitOptions o;
    o.train_fraction = share[i];
    Rng rng(1, "split");
    const Split s = make_random_split(19800, o, rng);
    EXPECT_EQ(s.test.size(), test[i]) << share[i];
    EXPECT_EQ(s.train.size() + s.test.size(), 19800u);
    EXPECT_TRUE(s.validation.empty());
  }
}

}  // namespace
}  // namespace cnclab
