// A narx experiment (model.type narx, trainer.stages) as an ordinary trial:
// its config, its one result file, and its numbers against the `kind: narx`
// study job (a second implementation of the same training and scoring).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/studies/contour_error/narx_job.hpp"
#include "cnclab/studies/contour_error/narx_metrics.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::error_message;
using testing::TempDir;

void register_metrics_once() {
  static const bool done = [] {
    register_contour_error_metrics();
    return true;
  }();
  (void)done;
}

const char* kDataset =
    "dataset:\n  generator: following_error\n  seed: 11\n  options:\n"
    "    path: {control_points: 12}\n    runs: 2\n    samples: 1200\n";

// The tiny study of narx_job_test.cpp as a trial (seed 1: its init seed).
std::string tiny_trial(const std::string& stages) {
  return std::string("name: tiny_trial\nseed: 1\n") + kDataset +
         "split: {mode: sequential_halves}\nnormalisation: {inputs: none, targets: none}\n"
         "model: {type: narx, input_delays: 2, feedback_delays: 2, hidden: 3}\n"
         "trainer:\n  stages: " +
         stages + "\n";
}
const char* kTwoStage =
    "[{mode: open_loop, type: trainbr, epochs: 30, min_gradient: 1.0e-8}, "
    "{mode: closed_loop, type: trainbr, epochs: 5, min_gradient: 1.0e-8}]";
const char* kOpenOnly = "[{mode: open_loop, type: trainbr, epochs: 30, min_gradient: 1.0e-8}]";

TEST(NarxTrial, ConfigErrorsNameTheKey) {
  register_metrics_once();
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
  std::string random = tiny_trial(kTwoStage);
  random.replace(random.find("{mode: sequential_halves}"), 25, "{train: 0.5}");
  EXPECT_NE(message(random).find("split.mode"), std::string::npos);
  EXPECT_NE(message(tiny_trial(kTwoStage) + "metrics: [rmse]\n").find("unknown metric"),
            std::string::npos);
}

TEST(NarxTrial, ResolvedConfigIsAFixedPointAndStagesChangeIt) {
  register_metrics_once();
  const LoadedExperiment a = parse_experiment(tiny_trial(kTwoStage), "t.yaml");
  const LoadedExperiment b = parse_experiment(a.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(a.resolved_yaml, b.resolved_yaml);
  ASSERT_EQ(a.spec.stages.size(), 2u);
  EXPECT_EQ(a.spec.stages[1].mode, StageMode::closed_loop);
  EXPECT_EQ(stages_text(a.spec.stages), "open_loop:trainbr+closed_loop:trainbr");
  const LoadedExperiment c = parse_experiment(tiny_trial(kOpenOnly), "t.yaml");
  EXPECT_NE(c.resolved_yaml, a.resolved_yaml);
}

// The same configs through the study job and as trials: bit-identical scores.
TEST(NarxTrial, MatchesTheStudyJobBitForBit) {
  register_metrics_once();
  TempDir dir;
  const fs::path job_file = dir.path() / "job.yaml";
  std::ofstream(job_file) << "kind: narx\nname: tiny\nseed: 5\n"
                          << kDataset
                          << "narx: {input_delays: 2, feedback_delays: 2, hidden: 3}\n"
                             "training:\n  open_loop: {epochs: 30}\n  closed_loop: {epochs: 5}\n"
                             "study:\n  methods: [two_stage, open_loop_only]\n  seeds: [1]\n";
  const NarxJobOutcome job = run_narx_job(load_narx_job(job_file), dir.path() / "results",
                                          dir.path() / "datasets", false, nullptr);
  RunOptions options;
  options.results_dir = dir.path() / "results";
  options.datasets_dir = dir.path() / "datasets";
  const char* stages[] = {kTwoStage, kOpenOnly};
  for (std::size_t i = 0; i < 2; ++i) {
    const RunOutcome o = run_experiment(parse_experiment(tiny_trial(stages[i]), "t.yaml"), options);
    ASSERT_TRUE(o.ok) << o.message;
    const NarxRun& run = job.result.runs[i];
    for (std::size_t a = 0; a < 2; ++a) {
      const std::string axis = job.result.axes[a];
      EXPECT_EQ(o.metrics.at("closed_loop_rms_" + axis), run.axes[a].rms_um) << i << axis;
      EXPECT_EQ(o.metrics.at("closed_loop_max_" + axis), run.axes[a].max_um) << i << axis;
      EXPECT_EQ(o.metrics.at("zero_rms_" + axis), job.result.zero_rms_um[a]);
    }
    EXPECT_EQ(o.metrics.at("contour_rms"), run.contour_rms_um);
    EXPECT_EQ(o.metrics.at("contour_max"), run.contour_max_um);
    EXPECT_EQ(o.metrics.at("stable"), 1.0);
    EXPECT_EQ(o.metrics.at("exact_contour_mean"), job.result.exact_contour_mean_um);
    EXPECT_EQ(o.metrics.at("taylor_mean_abs_diff"), job.result.estimates[0].mean_um);

    const RunRecord r = read_result(o.result_file);  // one standard result file
    ASSERT_TRUE(r.narx);
    ASSERT_EQ(r.narx->networks.size(), 2u);
    EXPECT_EQ(r.narx->networks[0].axis, "x");
    EXPECT_EQ(r.narx->networks[0].stages.size(), i == 0 ? 2u : 1u);
    EXPECT_EQ(r.narx->networks[0].stages[0].summary.history.size(), run.axes[0].open_epochs);
    EXPECT_EQ(r.narx->predictions.cols(), 600);
    EXPECT_EQ(r.metrics, o.metrics);
    EXPECT_EQ(r.provenance.status, "complete");
  }
}

}  // namespace
}  // namespace cnclab
