// Every field of a training record written by write_result and read back by
// read_result (the layout declared once, result_layout.hpp): an mlp run with
// both scalings, dropout evaluated both ways, a Levenberg-Marquardt history
// and upstream results; a narx run with two networks of two stages each.
// The records are made by hand with values no default has, so a field the
// writer skips or the reader leaves at its default fails.
#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/experiment/result_file.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

Eigen::MatrixXd counting(Eigen::Index rows, Eigen::Index cols, double start) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index j = 0; j < cols; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i)
      m(i, j) = start + 0.25 * static_cast<double>(i + rows * j);
  }
  return m;
}

Summary summary_with_history(std::size_t epochs, double start) {
  Summary s;
  s.termination = Termination::min_gradient;
  s.message = "gradient below 1e-7";
  s.best_epoch = epochs - 1;
  s.beta_guard_count = 2;
  for (std::size_t e = 1; e <= epochs; ++e) {
    const double x = start + static_cast<double>(e);
    s.history.push_back({e, x, x + 0.5, x / 10});
    s.lm_history.push_back({x, x + 1, x + 2, x + 3, x + 4, x + 5, x + 6, x + 7});
  }
  s.lm_initial = LmEpochRecord{start, 1.5, 2.5, 3.5, 4.5, 5.5, 6.5, 7.5};
  return s;
}

RunRecord common_record() {
  RunRecord r;
  r.experiment = "experiments/round_trip.yaml";
  r.resolved_yaml = "name: round_trip\nseed: 11\n";
  r.config_hash = "c0ffee";
  r.provenance.status = "complete";
  r.provenance.master_seed = 11;
  r.provenance.derived_seeds = {{"split", 12}};
  r.dataset_file = "datasets/round_trip.h5";
  r.dataset_hash = "deadbeef";
  r.input_names = {"x1", "x2"};
  r.input_units = {"mm", "mm/s"};
  r.target_names = {"e"};
  r.target_units = {"µm"};
  r.split = {{0, 3, 5}, {1, 4}, {2, 6, 7}};
  r.warnings = {"constant predictions"};
  r.upstream = {{"a.yaml", "results/a.h5", "id-a"}, {"b.yaml", "results/b.h5", "id-b"}};
  return r;
}

RunRecord mlp_record() {
  RunRecord r = common_record();
  r.model.inputs = 2;
  r.model.hidden = {3, 2};
  r.model.outputs = 1;
  r.model.hidden_activation = Activation::sigmoid;
  r.model.output_activation = Activation::tanh;
  r.model.dropout_keep_probability = 0.75;
  r.model.dropout_placement = DropoutPlacement::after_every_hidden;
  r.model.dropout_inference = DropoutInference::mc;
  r.model.dropout_mc_samples = 17;
  r.parameters = counting(2 * 3 + 3 + 3 * 2 + 2 + 2 + 1, 1, -1);
  r.input_scaling.method = Scaling::minmax;
  r.input_scaling.min = Eigen::Vector2d(-1, 2);
  r.input_scaling.max = Eigen::Vector2d(3, 4);
  r.input_scaling.y_min = 0;
  r.input_scaling.y_max = 2;
  r.target_scaling.method = Scaling::zscore;
  r.target_scaling.mean = Eigen::VectorXd::Constant(1, 0.5);
  r.target_scaling.std = Eigen::VectorXd::Constant(1, 2.5);
  r.trainer = "trainbr";
  r.training = summary_with_history(3, 10);
  r.test_loss = {0.3, 0.2, 0.1};
  r.test_predictions = counting(1, 3, 7);
  r.test_targets = counting(1, 3, 8);
  r.metrics = {{"test.rmse", 1.25}, {"validation.normalised_mse", 0.125}};
  r.metric_units = training_metric_units(r);
  r.other_inference =
      OtherInference{DropoutInference::deterministic, counting(1, 3, 9), {{"test.rmse", 1.5}}};
  return r;
}

RunRecord narx_record() {
  RunRecord r = common_record();
  r.trainer = "open_loop:trainbr+closed_loop:trainbr";
  r.training.termination = Termination::mu_max;
  r.training.message = "every stage's message";
  NarxRecord n;
  n.options.hidden = 3;
  n.options.hidden_activation = Activation::sigmoid;
  n.options.input_delays = 2;
  n.options.feedback_delays = 3;
  n.options.first_input_delay = 1;
  n.options.inputs = 2;  // two channels per network (not the default 1)
  for (const char* axis : {"e_x", "e_y"}) {
    NarxNetworkRecord net;
    net.axis = axis;
    net.inputs = {std::string("v_") + axis, std::string("direction_") + axis};
    net.target = axis;
    net.parameters = counting(19, 1, axis[2] == 'x' ? 1 : 2);
    net.seconds = axis[2] == 'x' ? 1.5 : 2.5;
    NarxStageRecord open{"open_loop", "trainbr", summary_with_history(2, 1), 0, false, 0};
    NarxStageRecord closed{"closed_loop", "trainbr", summary_with_history(3, 5), 40, true, 40};
    net.stages = {open, closed};
    n.networks.push_back(net);
  }
  n.predictions = counting(2, 5, 0);
  n.targets = counting(2, 5, 1);
  n.first_step = 3;
  r.narx = n;
  r.metrics = {{"validation.rmse", 2.0}};
  r.metric_units = training_metric_units(r);
  return r;
}

void expect_same_summary(const Summary& a, const Summary& b, bool lm) {
  EXPECT_EQ(a.termination, b.termination);
  EXPECT_EQ(a.message, b.message);
  EXPECT_EQ(a.best_epoch, b.best_epoch);
  ASSERT_EQ(a.history.size(), b.history.size());
  for (std::size_t i = 0; i < a.history.size(); ++i) {
    EXPECT_EQ(a.history[i].epoch, b.history[i].epoch);
    EXPECT_EQ(a.history[i].train_loss, b.history[i].train_loss);
    EXPECT_EQ(a.history[i].validation_loss, b.history[i].validation_loss);
    EXPECT_EQ(a.history[i].wall_seconds, b.history[i].wall_seconds);
  }
  if (!lm) return;
  EXPECT_EQ(a.beta_guard_count, b.beta_guard_count);
  ASSERT_EQ(a.lm_history.size(), b.lm_history.size());
  const auto lm_same = [](const LmEpochRecord& x, const LmEpochRecord& y) {
    EXPECT_EQ(x.sse, y.sse);
    EXPECT_EQ(x.ssw, y.ssw);
    EXPECT_EQ(x.alpha, y.alpha);
    EXPECT_EQ(x.beta, y.beta);
    EXPECT_EQ(x.gamma, y.gamma);
    EXPECT_EQ(x.mu, y.mu);
    EXPECT_EQ(x.gradient, y.gradient);
    EXPECT_EQ(x.curvature, y.curvature);
  };
  for (std::size_t i = 0; i < a.lm_history.size(); ++i) lm_same(a.lm_history[i], b.lm_history[i]);
  ASSERT_EQ(a.lm_initial.has_value(), b.lm_initial.has_value());
  if (a.lm_initial) lm_same(*a.lm_initial, *b.lm_initial);
}

void expect_same_common(const RunRecord& a, const RunRecord& b) {
  EXPECT_EQ(b.kind, "train");
  EXPECT_EQ(b.format_version, kResultFormatVersion);
  EXPECT_EQ(a.experiment, b.experiment);
  EXPECT_EQ(a.resolved_yaml, b.resolved_yaml);
  EXPECT_EQ(a.config_hash, b.config_hash);
  EXPECT_EQ(a.provenance.status, b.provenance.status);
  EXPECT_EQ(a.provenance.master_seed, b.provenance.master_seed);
  EXPECT_EQ(a.provenance.derived_seeds, b.provenance.derived_seeds);
  EXPECT_EQ(a.dataset_file, b.dataset_file);
  EXPECT_EQ(a.dataset_hash, b.dataset_hash);
  EXPECT_EQ(a.input_names, b.input_names);
  EXPECT_EQ(a.input_units, b.input_units);
  EXPECT_EQ(a.target_names, b.target_names);
  EXPECT_EQ(a.target_units, b.target_units);
  EXPECT_EQ(a.split.train, b.split.train);
  EXPECT_EQ(a.split.validation, b.split.validation);
  EXPECT_EQ(a.split.test, b.split.test);
  EXPECT_EQ(a.trainer, b.trainer);
  EXPECT_EQ(a.metrics, b.metrics);
  EXPECT_EQ(a.metric_units, b.metric_units);
  EXPECT_EQ(a.warnings, b.warnings);
  ASSERT_EQ(a.upstream.size(), b.upstream.size());
  for (std::size_t i = 0; i < a.upstream.size(); ++i) {
    EXPECT_EQ(a.upstream[i].experiment, b.upstream[i].experiment);
    EXPECT_EQ(a.upstream[i].result_file, b.upstream[i].result_file);
    EXPECT_EQ(a.upstream[i].identity, b.upstream[i].identity);
  }
}

TEST(ResultRoundTrip, MlpRecordReadsBackFieldForField) {
  TempDir dir;
  const RunRecord a = mlp_record();
  write_result(dir / "mlp.h5", a);
  const RunRecord b = read_result(dir / "mlp.h5");
  expect_same_common(a, b);
  EXPECT_FALSE(b.narx);
  EXPECT_EQ(a.model.inputs, b.model.inputs);
  EXPECT_EQ(a.model.hidden, b.model.hidden);
  EXPECT_EQ(a.model.outputs, b.model.outputs);
  EXPECT_EQ(a.model.hidden_activation, b.model.hidden_activation);
  EXPECT_EQ(a.model.output_activation, b.model.output_activation);
  EXPECT_EQ(a.model.dropout_keep_probability, b.model.dropout_keep_probability);
  EXPECT_EQ(a.model.dropout_placement, b.model.dropout_placement);
  EXPECT_EQ(a.model.dropout_inference, b.model.dropout_inference);
  EXPECT_EQ(a.model.dropout_mc_samples, b.model.dropout_mc_samples);
  EXPECT_EQ(a.parameters, b.parameters);
  EXPECT_EQ(a.input_scaling.method, b.input_scaling.method);
  EXPECT_EQ(a.input_scaling.min, b.input_scaling.min);
  EXPECT_EQ(a.input_scaling.max, b.input_scaling.max);
  EXPECT_EQ(a.input_scaling.y_min, b.input_scaling.y_min);
  EXPECT_EQ(a.input_scaling.y_max, b.input_scaling.y_max);
  EXPECT_EQ(a.target_scaling.method, b.target_scaling.method);
  EXPECT_EQ(a.target_scaling.mean, b.target_scaling.mean);
  EXPECT_EQ(a.target_scaling.std, b.target_scaling.std);
  expect_same_summary(a.training, b.training, true);
  EXPECT_EQ(a.test_loss, b.test_loss);
  EXPECT_EQ(a.test_predictions, b.test_predictions);
  EXPECT_EQ(a.test_targets, b.test_targets);
  ASSERT_TRUE(b.other_inference);
  EXPECT_EQ(a.other_inference->inference, b.other_inference->inference);
  EXPECT_EQ(a.other_inference->test_predictions, b.other_inference->test_predictions);
  EXPECT_EQ(a.other_inference->metrics, b.other_inference->metrics);
}

TEST(ResultRoundTrip, NarxRecordReadsBackFieldForField) {
  TempDir dir;
  const RunRecord a = narx_record();
  write_result(dir / "narx.h5", a);
  const RunRecord b = read_result(dir / "narx.h5");
  expect_same_common(a, b);
  EXPECT_EQ(a.training.termination, b.training.termination);
  EXPECT_EQ(a.training.message, b.training.message);
  ASSERT_TRUE(b.narx);
  const NarxRecord &n = *a.narx, &m = *b.narx;
  EXPECT_EQ(n.options.hidden, m.options.hidden);
  EXPECT_EQ(n.options.hidden_activation, m.options.hidden_activation);
  EXPECT_EQ(n.options.input_delays, m.options.input_delays);
  EXPECT_EQ(n.options.feedback_delays, m.options.feedback_delays);
  EXPECT_EQ(n.options.first_input_delay, m.options.first_input_delay);
  EXPECT_EQ(n.options.inputs, m.options.inputs);
  EXPECT_EQ(n.predictions, m.predictions);
  EXPECT_EQ(n.targets, m.targets);
  EXPECT_EQ(n.first_step, m.first_step);
  ASSERT_EQ(n.networks.size(), m.networks.size());
  for (std::size_t k = 0; k < n.networks.size(); ++k) {
    const auto &x = n.networks[k], &y = m.networks[k];
    EXPECT_EQ(x.axis, y.axis);
    EXPECT_EQ(x.inputs, y.inputs);
    EXPECT_EQ(x.target, y.target);
    EXPECT_EQ(x.parameters, y.parameters);
    EXPECT_EQ(x.seconds, y.seconds);
    ASSERT_EQ(x.stages.size(), y.stages.size());
    for (std::size_t s = 0; s < x.stages.size(); ++s) {
      EXPECT_EQ(x.stages[s].mode, y.stages[s].mode);
      EXPECT_EQ(x.stages[s].trainer, y.stages[s].trainer);
      EXPECT_EQ(x.stages[s].horizon, y.stages[s].horizon);
      EXPECT_EQ(x.stages[s].fallback, y.stages[s].fallback);
      EXPECT_EQ(x.stages[s].fallback_horizon, y.stages[s].fallback_horizon);
      expect_same_summary(x.stages[s].summary, y.stages[s].summary, true);
    }
  }
}

}  // namespace
}  // namespace cnclab
