// A trainbr run end to end (min-max normalisation, result file, show): the
// stored per-epoch history is read back through the raw HDF5 C API and
// checked against the trainbr update rules it must satisfy, and the stored
// min-max ranges against the training split of the dataset file.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

const char* kLmYaml = R"(name: tiny_trainbr
seed: 9
dataset: {generator: friedman1, options: {samples: 150, inputs: 6, noise_std: 1.0}}
normalisation: {inputs: minmax, targets: minmax}
model: {hidden: [6], hidden_activation: tanh, init: {weights: {type: xavier}}}
trainer: {type: trainbr, epochs: 15}
)";

// Any 1-D or 2-D numeric dataset as doubles (HDF5 converts), row-major.
std::vector<double> read_raw(hid_t file, const std::string& name, hsize_t* cols = nullptr) {
  const hid_t ds = H5Dopen2(file, name.c_str(), H5P_DEFAULT);
  EXPECT_GE(ds, 0) << name;
  const hid_t space = H5Dget_space(ds);
  hsize_t dims[2] = {0, 1};
  H5Sget_simple_extent_dims(space, dims, nullptr);
  std::vector<double> v(dims[0] * dims[1]);
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  if (cols) *cols = dims[1];
  H5Sclose(space);
  H5Dclose(ds);
  return v;
}

TEST(LmRun, TrainbrHistorySatisfiesTheUpdateRulesAndShowSummarisesIt) {
  TempDir dir;
  RunOptions o;
  o.results_dir = dir / "results";
  o.datasets_dir = dir / "datasets";
  const RunOutcome outcome = run_experiment(parse_experiment(kLmYaml, "tiny.yaml"), o);
  ASSERT_TRUE(outcome.ok) << outcome.message;

  const hid_t file = H5Fopen(outcome.result_file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  const auto sse = read_raw(file, "/history/sse"), ssw = read_raw(file, "/history/ssw");
  const auto alpha = read_raw(file, "/history/alpha"), beta = read_raw(file, "/history/beta");
  const auto gamma = read_raw(file, "/history/gamma"), mu = read_raw(file, "/history/mu");
  const auto train_loss = read_raw(file, "/history/train_loss");
  const auto train_idx = read_raw(file, "/split/train");
  const auto params = read_raw(file, "/model/parameters");
  ASSERT_FALSE(sse.empty());
  ASSERT_EQ(gamma.size(), sse.size());
  const double n = static_cast<double>(train_idx.size());  // one target per sample
  const double nw = static_cast<double>(params.size());
  for (std::size_t i = 0; i < sse.size(); ++i) {
    // alpha = gamma / (2 E_W), beta = (N - gamma) / (2 E_D): trainbr.hpp.
    EXPECT_NEAR(alpha[i], gamma[i] / (2 * ssw[i]), 1e-12 * alpha[i]) << "epoch " << i + 1;
    EXPECT_NEAR(beta[i], (n - gamma[i]) / (2 * sse[i]), 1e-12 * beta[i]) << "epoch " << i + 1;
    EXPECT_GT(gamma[i], 0.0);
    EXPECT_LT(gamma[i], nw);
    EXPECT_NEAR(train_loss[i], sse[i] / n, 1e-12 * train_loss[i]);
    EXPECT_GT(mu[i], 0.0);
  }
  // E_W of the stored parameters is the last SSW.
  double w2 = 0;
  for (double p : params) w2 += p * p;
  EXPECT_NEAR(ssw.back(), w2, 1e-12 * w2);

  // Min-max ranges: the training split's per-input minimum and maximum.
  const auto in_min = read_raw(file, "/model/input_scaling/min");
  const auto in_max = read_raw(file, "/model/input_scaling/max");
  H5Fclose(file);
  const RunRecord record = read_result(outcome.result_file);
  const hid_t data = H5Fopen(record.dataset_file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(data, 0);
  hsize_t d = 0;
  const auto inputs = read_raw(data, "/inputs", &d);
  H5Fclose(data);
  ASSERT_EQ(in_min.size(), d);
  for (hsize_t j = 0; j < d; ++j) {
    double lo = INFINITY, hi = -INFINITY;
    for (double s : train_idx) {
      const double v = inputs[static_cast<std::size_t>(s) * d + j];
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
    EXPECT_EQ(in_min[j], lo);
    EXPECT_EQ(in_max[j], hi);
  }

  // Round trip and `show`.
  EXPECT_EQ(record.trainer, "trainbr");
  EXPECT_EQ(record.input_scaling.method, Scaling::minmax);
  ASSERT_EQ(record.training.lm_history.size(), sse.size());
  EXPECT_EQ(record.training.lm_history.back().gamma, gamma.back());
  // The state before the first step: trainbr's start, gamma = N_w,
  // beta = (N - N_w) / (2 E_D), alpha = N_w / (2 E_W) (trainbr.hpp).
  ASSERT_TRUE(record.training.lm_initial);
  const LmEpochRecord& start = *record.training.lm_initial;
  EXPECT_EQ(start.gamma, nw);
  EXPECT_NEAR(start.beta, (n - nw) / (2 * start.sse), 1e-12 * start.beta);
  EXPECT_NEAR(start.alpha, nw / (2 * start.ssw), 1e-12 * start.alpha);
  EXPECT_GT(start.sse, sse.back());
  EXPECT_GT(record.training.lm_history.back().curvature, 0.0);
  // A file written before `curvature` and the initial state were recorded
  // still reads: NaN curvature, no initial state.
  const std::filesystem::path older = dir / "older.h5";
  std::filesystem::copy_file(outcome.result_file, older);
  const hid_t f = H5Fopen(older.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  EXPECT_GE(H5Ldelete(f, "/history/curvature", H5P_DEFAULT), 0);
  for (const char* series :
       {"sse", "ssw", "alpha", "beta", "gamma", "mu", "gradient", "curvature"}) {
    EXPECT_GE(
        H5Adelete_by_name(f, "/history", (std::string("initial_") + series).c_str(), H5P_DEFAULT),
        0)
        << series;
  }
  H5Fclose(f);
  const RunRecord old_record = read_result(older);
  EXPECT_FALSE(old_record.training.lm_initial);
  ASSERT_EQ(old_record.training.lm_history.size(), sse.size());
  EXPECT_TRUE(std::isnan(old_record.training.lm_history.back().curvature));
  EXPECT_EQ(old_record.training.lm_history.back().sse, sse.back());
  std::ostringstream shown;
  print_result(record, shown);
  EXPECT_NE(shown.str().find("training     trainbr, "), std::string::npos) << shown.str();
  EXPECT_NE(shown.str().find("gamma "), std::string::npos);
  EXPECT_NE(shown.str().find("alpha "), std::string::npos);
}

}  // namespace
}  // namespace cnclab
