// A sweep chooses on validation and reports test after: the default
// objective is the validation value of the experiment's first metric, and in
// a sweep whose validation-best and test-best points differ, the summary
// chooses the validation-best one and reports its test metrics as such.
//
// The case is built from data, not from a ranking: each trial's result is a
// real result file (from one real run) whose metrics evaluation_metrics
// computes from per-split predictions constructed with known errors:
//   point lr=0.1  validation error 0.1,  test error 1.0
//   point lr=0.2  validation error 0.5,  test error 0.05
//   point lr=0.3  validation error 0.3,  test error 0.3
// (each repeat r adds 0.01 r to both), so by hand the validation MSE is
// lowest at lr=0.1 and the test MSE at lr=0.2.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/sweep_report.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const char* kSelectionYaml = R"(name: pick
seed: 3
dataset: {generator: friedman1, options: {samples: 60, inputs: 5, noise_std: 0.5}}
split: {train: 0.5, validation: 0.25}
model: {hidden: [4], hidden_activation: tanh}
trainer: {type: sgdm, learning_rate: 0.1, momentum: 0.9, batch_size: 8, epochs: 1}
metrics: [mse, rmse]
)";

// Per point (plan order): the error of every validation and test prediction.
const std::map<std::string, std::pair<double, double>> kErrors = {
    {"0.1", {0.1, 1.0}}, {"0.2", {0.5, 0.05}}, {"0.3", {0.3, 0.3}}};

// `n` predictions off their targets by `error` (physical units; the scaled
// ones are not asked for).
SplitData off_by(double error, Eigen::Index n) {
  SplitData d;
  d.targets = Eigen::RowVectorXd::LinSpaced(n, -1.0, 2.0);
  d.predictions = d.targets.array() + error;
  return d;
}

class Selection : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "pick.yaml") << kSelectionYaml;
    RunOptions o;
    o.results_dir = dir_ / "results";
    o.datasets_dir = dir_ / "datasets";
    const RunOutcome run = run_experiment(load_experiment(dir_ / "pick.yaml"), o);
    ASSERT_TRUE(run.ok) << run.message;
    base_ = read_result(run.result_file);
    spec_.repeats = 2;
    spec_.set(*parse_sweep_values("trainer.learning_rate", "0.1,0.2,0.3"));
  }

  // The plan of spec_ with its trials' results written from kErrors.
  SweepPlan planned_with_results() {
    SweepPlan plan = plan_sweep(dir_ / "pick.yaml", {}, std::nullopt, spec_);
    for (const PlannedTrial& t : plan.trials) {
      const auto [validation, test] = kErrors.at(t.values.front());
      const double extra = 0.01 * static_cast<double>(t.repeat);
      RunRecord r = base_;
      r.metrics = evaluation_metrics(
          {{"validation", off_by(validation + extra, 15)}, {"test", off_by(test + extra, 15)}},
          {"validation.mse", "validation.rmse", "test.mse", "test.rmse"});
      fs::create_directories(dir_ / "sweep" / "trials");
      write_result(trial_result_path(dir_ / "sweep", t.id), r);
    }
    return plan;
  }

  TempDir dir_;
  RunRecord base_;
  SweepSpec spec_;
};

TEST_F(Selection, DefaultObjectiveIsTheValidationValueOfTheFirstMetric) {
  const SweepPlan plan = plan_sweep(dir_ / "pick.yaml", {}, std::nullopt, spec_);
  EXPECT_EQ(plan.objective.metric, "validation.mse");
  EXPECT_FALSE(plan.objective.maximize);
  EXPECT_EQ(plan.metrics, (std::vector<std::string>{"train.mse", "validation.mse", "test.mse",
                                                    "train.rmse", "validation.rmse", "test.rmse"}));
  EXPECT_EQ(objective_warning(plan), "");
  // A name without a split is its validation value; the older name too.
  EXPECT_EQ(resolve_objective(Objective{"rmse", false}, {"mse"}).metric, "validation.rmse");
  EXPECT_EQ(resolve_objective(Objective{"normalised_validation_mse", false}, {}).metric,
            "validation.normalised_mse");
  EXPECT_EQ(resolve_objective(std::nullopt, {"r2", "mse"}).metric, "validation.r2");
  EXPECT_TRUE(resolve_objective(std::nullopt, {"r2", "mse"}).maximize);
  EXPECT_EQ(resolve_objective(std::nullopt, {"test.rmse"}).metric, "validation.rmse");
}

TEST_F(Selection, ChoosesTheValidationBestAndReportsItsTestMetrics) {
  const SweepPlan plan = planned_with_results();
  const auto outcomes = read_trial_outcomes(dir_ / "sweep", plan);
  // The case discriminates: by the trials' own test metrics lr=0.2 is best.
  std::map<std::string, double> test_mse;
  for (std::size_t i = 0; i < plan.trials.size(); ++i) {
    test_mse[plan.trials[i].values.front()] += outcomes[i].metrics.at("test.mse") / 2;
  }
  EXPECT_LT(test_mse.at("0.2"), test_mse.at("0.1"));
  EXPECT_LT(test_mse.at("0.2"), test_mse.at("0.3"));

  const SweepSummary s = summarize(plan, outcomes);
  ASSERT_GE(s.best_trial, 0);
  EXPECT_EQ(s.points.front().values.front(), "0.1");
  // Its test metrics, by hand: errors 1.0 and 1.01 over the two repeats.
  const double chosen_test_mse = (1.0 * 1.0 + 1.01 * 1.01) / 2;
  EXPECT_NEAR(s.points.front().mean.at("test.mse"), chosen_test_mse, 1e-12);

  std::ostringstream text;
  print_summary(text, plan, outcomes, s, dir_ / "sweep");
  const std::string out = text.str();
  EXPECT_NE(out.find("validation.mse [1] (min)"), std::string::npos) << out;
  EXPECT_NE(out.find("chosen point, test (rank 1, chosen by validation.mse"), std::string::npos)
      << out;
  EXPECT_NE(out.find("  test.mse [1]   " + format_metric(chosen_test_mse)), std::string::npos)
      << out;  // aligned under test.rmse [1]
  EXPECT_EQ(out.find("WARNING"), std::string::npos) << out;
  // The ranking table holds the objective's split only.
  const std::string header = out.substr(out.find('\n') + 1, out.find('\n', out.find('\n') + 1));
  EXPECT_EQ(header.find("test."), std::string::npos) << header;

  // summary.h5 records the choice and the chosen point's test metrics.
  write_summary(dir_ / "summary.h5", plan, outcomes, s);
  const H5File f = H5File::open_read(dir_ / "summary.h5");
  EXPECT_EQ(f.attribute_string("/selected", "objective_metric"), "validation.mse");
  EXPECT_EQ(f.attribute_string("/selected", "trial"),
            plan.trials[static_cast<std::size_t>(s.best_trial)].id);
  EXPECT_NEAR(f.attribute_double("/selected/metrics", "test.mse"), chosen_test_mse, 1e-12);
  EXPECT_EQ(f.attribute_string("/selected/units", "test.mse"), "1");
  EXPECT_EQ(f.units("/trials/metrics/validation.mse"), "1");
  // Read back, the summary ranks and reports the same.
  const StoredSummary stored = read_summary(dir_ / "summary.h5");
  EXPECT_EQ(summarize(stored.plan, stored.outcomes).points.front().values.front(), "0.1");
}

// Asked for, a test objective chooses the test-best point, with a warning
// where the sweep runs and under its table.
TEST_F(Selection, AnExplicitTestObjectiveIsAllowedWithAWarning) {
  spec_.objective = Objective{"test.mse", false};
  const SweepPlan plan = planned_with_results();
  EXPECT_EQ(plan.objective.metric, "test.mse");
  EXPECT_NE(objective_warning(plan).find("the point is chosen on test data"), std::string::npos);
  const auto outcomes = read_trial_outcomes(dir_ / "sweep", plan);
  const SweepSummary s = summarize(plan, outcomes);
  EXPECT_EQ(s.points.front().values.front(), "0.2");
  std::ostringstream text;
  print_summary(text, plan, outcomes, s, dir_ / "sweep");
  EXPECT_NE(text.str().find("WARNING the objective test.mse ranks the points by the test split"),
            std::string::npos)
      << text.str();
}

TEST_F(Selection, WithoutAValidationSplitTheDefaultObjectiveIsRefused) {
  const std::string err = testing::error_message<ConfigError>(
      [&] { plan_sweep(dir_ / "pick.yaml", {"split.validation=0"}, std::nullopt, spec_); });
  EXPECT_NE(err.find("objective metric 'validation.mse' is not among"), std::string::npos) << err;
  EXPECT_NE(err.find("the experiment has no validation split"), std::string::npos) << err;
  // Naming the objective (here the training MSE) is the way out.
  spec_.objective = Objective{"train.mse", false};
  EXPECT_NO_THROW(plan_sweep(dir_ / "pick.yaml", {"split.validation=0"}, std::nullopt, spec_));
}

}  // namespace
}  // namespace cnclab
