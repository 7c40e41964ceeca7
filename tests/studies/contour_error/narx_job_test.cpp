#include "cnclab/studies/contour_error/narx_job.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::error_message;
using testing::TempDir;

// A tiny study: 1200 samples of a short path, 2 runs, a 3-neuron NARX with 2
// delays, a few epochs.
std::string tiny(const std::string& extra = "") {
  return "kind: narx\nname: tiny\nseed: 5\n"
         "dataset:\n  generator: following_error\n  seed: 11\n  options:\n"
         "    path: {control_points: 12}\n    runs: 2\n    samples: 1200\n"
         "narx: {input_delays: 2, feedback_delays: 2, hidden: 3}\n"
         "training:\n  open_loop: {epochs: 30}\n  closed_loop: {epochs: 5}\n"
         "study:\n  methods: [two_stage, open_loop_only]\n  seeds: [1]\n  workers: 2\n" +
         extra;
}

fs::path write(const TempDir& dir, const std::string& text) {
  const fs::path file = dir.path() / "job.yaml";
  std::ofstream(file) << text;
  return file;
}

std::size_t files_under(const fs::path& dir) {
  std::size_t n = 0;
  std::error_code ec;
  for (const auto& e : fs::recursive_directory_iterator(dir, ec)) n += e.is_regular_file() ? 1 : 0;
  return n;
}

TEST(NarxJob, BadInputsAreConfigErrorsNamingTheKeyAndWriteNothing) {
  TempDir dir;
  auto message = [&](const std::string& yaml, const std::vector<std::string>& overrides) {
    return error_message<ConfigError>([&] {
      const NarxJob job = load_narx_job(write(dir, yaml), overrides);
      run_narx_job(job, dir.path() / "results", dir.path() / "datasets", false, nullptr);
    });
  };
  EXPECT_NE(message(tiny(), {"narx.input_delays=0"}).find("narx.input_delays"), std::string::npos);
  EXPECT_NE(message(tiny(), {"narx.feedback_delays=0"}).find("feedback_delays"), std::string::npos);
  EXPECT_NE(message(tiny("  architectures: [{hidden: 4, delays: 0}]\n"), {}).find("delays = 0"),
            std::string::npos);
  EXPECT_NE(message(tiny(), {"dataset.options.limits.velocity=0"}).find("limits.velocity"),
            std::string::npos);
  EXPECT_NE(message(tiny(), {"dataset.options.limits.acceleration=-1"}).find("acceleration"),
            std::string::npos);
  EXPECT_NE(message(tiny(), {"study.methods=[three_stage]"}).find("three_stage"),
            std::string::npos);
  EXPECT_NE(message(tiny(), {"narx.hiden=3"}).find("hiden"), std::string::npos);
  EXPECT_NE(message(tiny(), {"training.closed_loop.mu=-1"}).find("closed_loop.mu"),
            std::string::npos);
  // A profile not asked for is only read; one the file does not define
  // leaves it unchanged (core/config.hpp: reproduce --quick over folders whose
  // files do not all have a quick profile).
  const fs::path with_profile = write(dir, tiny("profiles: {quick: {study.seeds: [2]}}\n"));
  EXPECT_EQ(load_narx_job(with_profile).study.seeds, std::vector<std::uint64_t>{1});
  EXPECT_EQ(load_narx_job(with_profile, {}, "quick").study.seeds, std::vector<std::uint64_t>{2});
  EXPECT_EQ(load_narx_job(with_profile, {}, "slow").study.seeds, std::vector<std::uint64_t>{1});
  EXPECT_EQ(files_under(dir.path() / "results"), 0u);
  EXPECT_EQ(files_under(dir.path() / "datasets"), 0u);
}

TEST(NarxJob, NanInTheDatasetIsAnErrorNamingTheSample) {
  Dataset d;
  d.generator = "following_error";
  d.inputs = Eigen::MatrixXd::Zero(2, 100);
  d.targets = Eigen::MatrixXd::Zero(2, 100);
  d.input_names = {"v_x", "v_y"};
  d.input_units = {"1", "1"};
  d.target_names = {"e_x", "e_y"};
  d.target_units = {"1", "1"};
  EXPECT_EQ(error_message<Error>([&] { check_narx_dataset(d, "d.h5"); }), "no error");
  d.targets(1, 42) = std::numeric_limits<double>::quiet_NaN();
  const std::string m = error_message<Error>([&] { check_narx_dataset(d, "d.h5"); });
  EXPECT_NE(m.find("e_y"), std::string::npos) << m;
  EXPECT_NE(m.find("42"), std::string::npos) << m;
}

// Runs the tiny study end to end: structure, closed-loop validation over the
// whole second half, a trained network better than predicting zero, the
// result reused on the second call and rerun when the config changes.
TEST(NarxJob, RunsWritesAndReusesTheStudy) {
  TempDir dir;
  const fs::path file = write(dir, tiny());
  const NarxJob job = load_narx_job(file);
  const NarxJobOutcome first =
      run_narx_job(job, dir.path() / "results", dir.path() / "datasets", false, nullptr);
  EXPECT_FALSE(first.reused);
  ASSERT_TRUE(fs::exists(first.file));
  const NarxStudyResult& r = first.result;
  EXPECT_EQ(r.train_samples, 600u);
  EXPECT_EQ(r.validation_samples, 600u);
  ASSERT_EQ(r.runs.size(), 2u);
  EXPECT_EQ(r.runs[0].method, NarxMethod::two_stage);
  EXPECT_EQ(r.runs[1].method, NarxMethod::open_loop_only);
  for (const auto& run : r.runs) {
    ASSERT_EQ(run.axes.size(), 2u);
    for (std::size_t a = 0; a < 2; ++a) {
      EXPECT_TRUE(run.axes[a].stable);
      EXPECT_LT(run.axes[a].rms_um, r.zero_rms_um[a]) << to_string(run.method) << " axis " << a;
      EXPECT_GE(run.axes[a].max_um, run.axes[a].rms_um);
    }
    EXPECT_TRUE(std::isfinite(run.contour_rms_um));
  }
  EXPECT_EQ(r.runs[0].axes[0].closed_epochs > 0, true);
  EXPECT_EQ(r.runs[1].axes[0].closed_epochs, 0u);
  ASSERT_EQ(r.estimates.size(), 3u);
  // Taylor is second-order exact: closer to the exact contour error than the
  // tangent line on a curved path.
  EXPECT_LE(r.estimates[0].mean_um, r.estimates[1].mean_um);
  EXPECT_EQ(r.series.cols(), 600);

  const NarxStudyResult back = read_narx_result(first.file);
  EXPECT_EQ(back.config_hash, job.config_hash);
  EXPECT_EQ(back.runs[1].axes[1].rms_um, r.runs[1].axes[1].rms_um);

  const NarxJobOutcome again =
      run_narx_job(job, dir.path() / "results", dir.path() / "datasets", false, nullptr);
  EXPECT_TRUE(again.reused);
  const NarxJob changed = load_narx_job(file, {"study.stable_bound=20"});
  EXPECT_NE(changed.config_hash, job.config_hash);
  EXPECT_NE(narx_result_path(changed, "r"), narx_result_path(job, "r"));
}

}  // namespace
}  // namespace cnclab
