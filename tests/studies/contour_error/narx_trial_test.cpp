// A narx experiment (model.type narx, trainer.stages) as an ordinary trial:
// its config, its one result file, and its metrics against the stored
// prediction.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"
#include "studies/contour_error/metrics_once.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::error_message;
using testing::TempDir;

const char* kDataset =
    "dataset:\n  generator: following_error\n  seed: 11\n  options:\n"
    "    path: {control_points: 12}\n    runs: 2\n    samples: 1200\n";

// A tiny NARX experiment (1200 samples, 2 + 2 delays, 3 hidden units).
std::string tiny_trial(const std::string& stages) {
  return std::string("name: tiny_trial\nseed: 1\n") + kDataset +
         "split: {mode: sequential_halves}\nnormalisation: {inputs: none, targets: none}\n"
         "model: {type: narx, input_delays: 2, feedback_delays: 2, hidden: 3}\n"
         "trainer:\n  stages: " +
         stages + "\n";
}
// Results and datasets below `dir`.
RunOptions run_options_in(const TempDir& dir) {
  RunOptions options;
  options.results_dir = dir.path() / "results";
  options.datasets_dir = dir.path() / "datasets";
  return options;
}

const char* kTwoStage =
    "[{mode: open_loop, type: trainbr, epochs: 30, min_gradient: 1.0e-8}, "
    "{mode: closed_loop, type: trainbr, epochs: 5, min_gradient: 1.0e-8}]";
const char* kOpenOnly = "[{mode: open_loop, type: trainbr, epochs: 30, min_gradient: 1.0e-8}]";

TEST(NarxTrial, ConfigErrorsNameTheKey) {
  testing::register_contour_error_metrics_once();
  const auto message = [](const std::string& yaml) {
    return error_message<ConfigError>([&] { parse_experiment(yaml, "t.yaml"); });
  };
  EXPECT_NE(message(tiny_trial("[]")).find("trainer.stages"), std::string::npos);
  EXPECT_NE(message(tiny_trial("[{mode: open_loop, type: sgdm}]")).find("type"), std::string::npos);
  EXPECT_NE(message(tiny_trial("[{mode: open_loop, type: trainbr, epoch: 3}]"))
                .find("did you mean 'epochs'"),
            std::string::npos);
  EXPECT_NE(message(tiny_trial("[{mode: half_loop, type: trainbr}]")).find("mode"),
            std::string::npos);
  EXPECT_NE(message(tiny_trial("[{mode: open_loop, horizon: 100, type: trainbr}]"))
                .find("horizon = 100: applies to closed_loop stages only"),
            std::string::npos);
  // horizon 0 (one window) is the default and not written, so results
  // trained before the key existed keep their identity.
  const auto windowed =
      parse_experiment(tiny_trial("[{mode: closed_loop, horizon: 100, type: trainbr}]"), "t.yaml");
  EXPECT_EQ(windowed.spec.stages.at(0).horizon, 100u);
  EXPECT_NE(windowed.resolved_yaml.find("horizon: 100"), std::string::npos);
  EXPECT_EQ(
      parse_experiment(tiny_trial("[{mode: closed_loop, horizon: 0, type: trainbr}]"), "t.yaml")
          .resolved_yaml.find("horizon"),
      std::string::npos);
  std::string random = tiny_trial(kTwoStage);
  random.replace(random.find("{mode: sequential_halves}"), 25, "{train: 0.5}");
  EXPECT_NE(message(random).find("split.mode"), std::string::npos);
  EXPECT_NE(message(tiny_trial(kTwoStage) + "metrics: [rmse]\n").find("unknown metric"),
            std::string::npos);
  // A narx run's metrics are of its validation half: there is no test.*.
  EXPECT_NE(message(tiny_trial(kTwoStage) + "metrics: [test.contour_rms]\n")
                .find("model.type narx has no test split"),
            std::string::npos);
  EXPECT_NO_THROW(
      parse_experiment(tiny_trial(kTwoStage) + "metrics: [validation.contour_rms]\n", "t.yaml"));
}

TEST(NarxTrial, ResolvedConfigIsAFixedPointAndStagesChangeIt) {
  testing::register_contour_error_metrics_once();
  const LoadedExperiment a = parse_experiment(tiny_trial(kTwoStage), "t.yaml");
  const LoadedExperiment b = parse_experiment(a.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(a.resolved_yaml, b.resolved_yaml);
  ASSERT_EQ(a.spec.stages.size(), 2u);
  EXPECT_EQ(a.spec.stages[1].mode, StageMode::closed_loop);
  EXPECT_EQ(stages_text(a.spec.stages), "open_loop:trainbr+closed_loop:trainbr");
  const LoadedExperiment c = parse_experiment(tiny_trial(kOpenOnly), "t.yaml");
  EXPECT_NE(c.resolved_yaml, a.resolved_yaml);
}

// Root-mean-square of v.
double rms(const Eigen::VectorXd& v) {
  return std::sqrt(v.squaredNorm() / static_cast<double>(v.size()));
}

// The metrics against the run's stored closed-loop prediction and the
// dataset it names, recomputed here from the result file (µm: mapminmax
// inverted with the dataset's ranges); two-stage training beats predicting
// zero. (Before the `kind: narx` job was removed, these trials matched it
// bit for bit.)
TEST(NarxTrial, MetricsAgreeWithTheStoredPrediction) {
  testing::register_contour_error_metrics_once();
  TempDir dir;
  const RunOptions options = run_options_in(dir);
  const char* stages[] = {kTwoStage, kOpenOnly};
  for (std::size_t i = 0; i < 2; ++i) {
    const RunOutcome o = run_experiment(parse_experiment(tiny_trial(stages[i]), "t.yaml"), options);
    ASSERT_TRUE(o.ok) << o.message;
    const RunRecord r = read_result(o.result_file);  // one standard result file
    ASSERT_TRUE(r.narx);
    ASSERT_EQ(r.narx->networks.size(), 2u);
    EXPECT_EQ(r.narx->networks[0].stages.size(), i == 0 ? 2u : 1u);
    EXPECT_EQ(r.narx->networks[0].stages[0].summary.history.size(), 30u);
    EXPECT_EQ(r.metrics, o.metrics);
    EXPECT_EQ(r.provenance.status, "complete");
    EXPECT_EQ(r.metrics.at("validation.stable"), 1.0);
    const Dataset d = read_dataset(r.dataset_file);
    const FollowingErrorRanges ranges = following_error_ranges(d);
    const auto first = static_cast<Eigen::Index>(r.narx->first_step);
    const Eigen::Index steps = r.narx->predictions.cols() - first;
    EXPECT_EQ(r.narx->predictions.cols(), 600);  // the validation half of 1200
    for (Eigen::Index a = 0; a < 2; ++a) {
      const std::string axis = r.narx->networks[static_cast<std::size_t>(a)].axis;
      const ColumnRange& range = ranges.following_error[static_cast<std::size_t>(a)];
      Eigen::VectorXd error(steps), target(r.narx->targets.cols());
      for (Eigen::Index t = 0; t < r.narx->targets.cols(); ++t) {
        target[t] = to_physical(r.narx->targets(a, t), range);
      }
      for (Eigen::Index t = 0; t < steps; ++t) {
        error[t] = to_physical(r.narx->predictions(a, first + t), range) - target[first + t];
      }
      const double rms_um = r.metrics.at("validation.closed_loop_rms_" + axis);
      EXPECT_NEAR(rms_um, rms(error), 1e-9 * rms_um) << i << axis;
      EXPECT_NEAR(r.metrics.at("validation.closed_loop_max_" + axis), error.cwiseAbs().maxCoeff(),
                  1e-9 * rms_um);
      // The zero predictor over the same steps as the closed loop: from the
      // first predicted step, not over the delays' measured initial states.
      const Eigen::VectorXd scored = target.tail(steps);
      EXPECT_NEAR(r.metrics.at("validation.zero_rms_" + axis), rms(scored), 1e-9 * rms(scored))
          << axis;
      EXPECT_NEAR(r.metrics.at("validation.zero_max_" + axis), scored.cwiseAbs().maxCoeff(),
                  1e-9 * rms(scored))
          << axis;
      if (i == 0) {
        EXPECT_LT(rms_um, r.metrics.at("validation.zero_rms_" + axis)) << axis;
      }
    }
  }
}

// fallback_horizon: a closed-loop stage that stops on mu_max is tried again
// from its starting weights (windows of 50 steps, then the whole series, half
// the epochs each), and the weights kept are those with the lower
// whole-series SSE: checked against the closed-loop SSE of the stored
// parameters, simulated here on the training half of the dataset.
// mu_max = mu makes the first rejected step stop the stage.
TEST(NarxTrial, SecondTryKeepsTheLowerWholeSeriesSse) {
  testing::register_contour_error_metrics_once();
  TempDir dir;
  const RunOptions options = run_options_in(dir);
  const std::string stages =
      "[{mode: open_loop, type: trainbr, epochs: 30}, {mode: closed_loop, type: trainbr, "
      "epochs: 6, mu: 1.0e-3, mu_max: 1.0e-3, fallback_horizon: 50}]";
  std::size_t retried = 0;
  for (const char* seed : {"seed: 1", "seed: 2", "seed: 3"}) {
    std::string yaml = tiny_trial(stages);
    yaml.replace(yaml.find("seed: 1"), 7, seed);
    const RunOutcome o = run_experiment(parse_experiment(yaml, "t.yaml"), options);
    ASSERT_TRUE(o.ok) << o.message;
    const RunRecord r = read_result(o.result_file);
    const Dataset d = read_dataset(r.dataset_file);
    const Narx narx(r.narx->options);
    const auto half = static_cast<Eigen::Index>(r.split.train.size());
    for (std::size_t a = 0; a < r.narx->networks.size(); ++a) {
      const NarxNetworkRecord& net = r.narx->networks[a];
      ASSERT_GE(net.stages.size(), 2u);
      const Summary& first = net.stages[1].summary;
      const auto final_sse = [](const Summary& s) {
        return s.lm_history.empty() ? s.lm_initial->sse : s.lm_history.back().sse;
      };
      const bool failed =
          first.termination == Termination::mu_max || first.termination == Termination::diverged;
      ASSERT_EQ(net.stages.size(), failed ? 4u : 2u) << seed << " " << net.axis;
      if (!failed) continue;
      ++retried;
      EXPECT_TRUE(net.stages[2].fallback && net.stages[3].fallback);
      EXPECT_EQ(net.stages[2].horizon, 50u);
      EXPECT_EQ(net.stages[3].horizon, 0u);
      EXPECT_LE(net.stages[2].summary.history.size(), 3u);
      EXPECT_LE(net.stages[3].summary.history.size(), 3u);
      const double kept = std::min(final_sse(first), final_sse(net.stages[3].summary));
      const auto row = static_cast<Eigen::Index>(a);
      const Eigen::VectorXd v = d.inputs.row(row).head(half).transpose();
      const Eigen::VectorXd e = d.targets.row(row).head(half).transpose();
      const double sse =
          (narx.simulate_closed_loop(net.parameters, v, e) - e.tail(half - narx.first_step()))
              .squaredNorm();
      EXPECT_NEAR(sse, kept, 1e-9 * kept) << seed << " " << net.axis;
    }
  }
  EXPECT_GT(retried, 0u) << "no closed-loop stage stopped on mu_max: the test checks nothing";
}

// The number of stage files in a datasets folder's stage cache.
std::size_t cached_stages(const RunOptions& options) {
  const fs::path dir = options.datasets_dir / "narx-stages";
  if (!fs::is_directory(dir)) return 0;
  return static_cast<std::size_t>(
      std::distance(fs::directory_iterator(dir), fs::directory_iterator{}));
}

// Shared stages (experiment/narx_stage_cache.hpp): a two-stage run whose
// open-loop stages another run trained reads them back and ends bit for bit
// where a run that trains everything ends (checked against such a run in a
// folder of its own); other starting weights or options are other stages;
// a damaged cache file is trained again.
TEST(NarxTrial, SharedStagesEndBitForBitWhereTrainingEnds) {
  testing::register_contour_error_metrics_once();
  TempDir dir;  // one per test: two folders in it
  RunOptions fresh, shared;
  fresh.results_dir = dir / "fresh_results";
  fresh.datasets_dir = dir / "fresh_datasets";
  shared.results_dir = dir / "shared_results";
  shared.datasets_dir = dir / "shared_datasets";
  const auto run = [](const std::string& yaml, const RunOptions& options) {
    const RunOutcome o = run_experiment(parse_experiment(yaml, "t.yaml"), options);
    EXPECT_TRUE(o.ok) << o.message;
    return read_result(o.result_file);
  };
  const RunRecord trained = run(tiny_trial(kTwoStage), fresh);
  EXPECT_EQ(cached_stages(fresh), 4u);  // 2 axes x 2 stages

  run(tiny_trial(kOpenOnly), shared);
  EXPECT_EQ(cached_stages(shared), 2u);
  const RunRecord reused = run(tiny_trial(kTwoStage), shared);
  EXPECT_EQ(cached_stages(shared), 4u);  // only the closed-loop stages were new
  ASSERT_EQ(reused.narx->networks.size(), trained.narx->networks.size());
  for (std::size_t a = 0; a < trained.narx->networks.size(); ++a) {
    const NarxNetworkRecord &x = trained.narx->networks[a], &y = reused.narx->networks[a];
    EXPECT_EQ(x.parameters, y.parameters) << x.axis;  // exact
    ASSERT_EQ(x.stages.size(), y.stages.size());
    for (std::size_t k = 0; k < x.stages.size(); ++k) {
      const Summary &p = x.stages[k].summary, &q = y.stages[k].summary;
      EXPECT_EQ(p.termination, q.termination);
      ASSERT_EQ(p.lm_history.size(), q.lm_history.size());
      for (std::size_t i = 0; i < p.lm_history.size(); ++i) {
        EXPECT_EQ(p.lm_history[i].sse, q.lm_history[i].sse);
        EXPECT_EQ(p.lm_history[i].mu, q.lm_history[i].mu);
      }
      EXPECT_EQ(p.lm_initial->sse, q.lm_initial->sse);
    }
  }
  EXPECT_EQ(trained.metrics, reused.metrics);

  // Another seed (other starting weights) and another epoch count are new stages.
  std::string seed2 = tiny_trial(kOpenOnly);
  seed2.replace(seed2.find("seed: 1"), 7, "seed: 2");
  run(seed2, shared);
  EXPECT_EQ(cached_stages(shared), 6u);
  std::string epochs = tiny_trial(kOpenOnly);
  epochs.replace(epochs.find("epochs: 30"), 10, "epochs: 29");
  run(epochs, shared);
  EXPECT_EQ(cached_stages(shared), 8u);

  // Damaged files are trained again and replaced.
  for (const auto& f : fs::directory_iterator(shared.datasets_dir / "narx-stages")) {
    std::ofstream(f.path(), std::ios::trunc) << "not hdf5";
  }
  EXPECT_EQ(run(tiny_trial(kTwoStage), shared).metrics, trained.metrics);
}

}  // namespace
}  // namespace cnclab
