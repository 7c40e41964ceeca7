// A result written by the runner, read back (1) through the raw HDF5 C API,
// independently of the writer classes, recomputing the metrics from the
// stored predictions and targets, and (2) through read_result (round trip).
#include "cnclab/experiment/result_file.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>

#include <cmath>
#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/runner.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

const char* kResultFileYaml = R"(name: tiny
seed: 5
dataset: {generator: friedman1, options: {samples: 120, inputs: 6, noise_std: 0.5}}
model: {hidden: [8], hidden_activation: tanh, init: {weights: {type: xavier}}}
trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 8, epochs: 4}
)";

std::vector<double> read_raw(hid_t file, const char* name, hsize_t* rows, hsize_t* cols) {
  const hid_t ds = H5Dopen2(file, name, H5P_DEFAULT);
  const hid_t space = H5Dget_space(ds);
  hsize_t dims[2] = {0, 1};
  const int rank = H5Sget_simple_extent_dims(space, dims, nullptr);
  EXPECT_EQ(rank, 2) << name;
  *rows = dims[0];
  *cols = dims[1];
  std::vector<double> v(dims[0] * dims[1]);
  H5Dread(ds, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(space);
  H5Dclose(ds);
  return v;
}

double read_attr(hid_t file, const char* object, const char* name) {
  const hid_t a = H5Aopen_by_name(file, object, name, H5P_DEFAULT, H5P_DEFAULT);
  double v = std::nan("");
  H5Aread(a, H5T_NATIVE_DOUBLE, &v);
  H5Aclose(a);
  return v;
}

class ResultFile : public ::testing::Test {
 protected:
  void SetUp() override {
    RunOptions o;
    o.results_dir = dir_ / "results";
    o.datasets_dir = dir_ / "datasets";
    outcome_ = run_experiment(parse_experiment(kResultFileYaml, "tiny.yaml"), o);
    ASSERT_TRUE(outcome_.ok) << outcome_.message;
  }
  TempDir dir_;
  RunOutcome outcome_;
};

TEST_F(ResultFile, MetricsRecomputedFromRawDatasetsMatchStoredOnes) {
  const hid_t file = H5Fopen(outcome_.result_file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  hsize_t pr, pc, tr, tc;
  const auto pred = read_raw(file, "/test/predictions", &pr, &pc);
  const auto targ = read_raw(file, "/test/targets", &tr, &tc);
  EXPECT_EQ(pr, 36u);  // 30 % of 120 samples
  EXPECT_EQ(pc, 1u);
  ASSERT_EQ(pred.size(), targ.size());
  double sse = 0, sae = 0, max_abs = 0;
  for (std::size_t i = 0; i < pred.size(); ++i) {
    const double e = pred[i] - targ[i];
    sse += e * e;
    sae += std::abs(e);
    max_abs = std::max(max_abs, std::abs(e));
  }
  const double n = static_cast<double>(pred.size());
  EXPECT_DOUBLE_EQ(read_attr(file, "/metrics", "test.mse"), sse / n);
  EXPECT_DOUBLE_EQ(read_attr(file, "/metrics", "test.rmse"), std::sqrt(sse / n));
  EXPECT_DOUBLE_EQ(read_attr(file, "/metrics", "test.mae"), sae / n);
  EXPECT_DOUBLE_EQ(read_attr(file, "/metrics", "test.max_abs_error"), max_abs);
  EXPECT_EQ(read_attr(file, "/", "complete"), 1.0);
  H5Fclose(file);
}

TEST_F(ResultFile, RoundTripThroughReadResult) {
  const RunRecord r = read_result(outcome_.result_file);
  EXPECT_EQ(r.experiment, "tiny");
  EXPECT_EQ(r.provenance.status, "complete");
  EXPECT_EQ(r.provenance.master_seed, 5u);
  EXPECT_EQ(r.training.history.size(), 4u);
  EXPECT_EQ(r.test_loss.size(), 4u);
  EXPECT_EQ(r.split.train.size() + r.split.test.size(), 120u);
  EXPECT_EQ(r.model.hidden, std::vector<std::size_t>{8});
  EXPECT_EQ(static_cast<std::size_t>(r.parameters.size()), (6u + 1) * 8 + (8 + 1) * 1);
  EXPECT_EQ(r.metrics, outcome_.metrics);
  // The stored config is itself a valid experiment that resolves identically.
  EXPECT_EQ(parse_experiment(r.resolved_yaml, "stored").resolved_yaml, r.resolved_yaml);
}

TEST_F(ResultFile, FileWithoutCompletionMarkIsRejected) {
  const auto copy = dir_ / "copy.h5";
  std::filesystem::copy_file(outcome_.result_file, copy);
  const hid_t file = H5Fopen(copy.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  H5Adelete(file, "complete");
  H5Fclose(file);
  try {
    read_result(copy);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("incomplete"), std::string::npos);
  }
}

TEST_F(ResultFile, TruncatedAndForeignFilesAreIoErrors) {
  const auto cut = dir_ / "cut.h5";
  std::filesystem::copy_file(outcome_.result_file, cut);
  std::filesystem::resize_file(cut, std::filesystem::file_size(cut) / 3);
  EXPECT_THROW(read_result(cut), IoError);
  // A valid HDF5 file that is not a result (a dataset file).
  const auto dataset = *std::filesystem::directory_iterator(dir_ / "datasets");
  EXPECT_THROW(read_result(dataset.path()), IoError);
}

// /metrics holds numbers only (h5py's
// {k: float(v) for k, v in f["metrics"].attrs.items()} works), each metric's
// unit in /metrics/units; read through the raw C API.
TEST_F(ResultFile, MetricsAttributesAreNumbersAndUnitsSitApart) {
  const hid_t file = H5Fopen(outcome_.result_file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(file, 0);
  std::vector<std::string> names;
  const hid_t group = H5Gopen2(file, "/metrics", H5P_DEFAULT);
  H5Aiterate2(
      group, H5_INDEX_NAME, H5_ITER_INC, nullptr,
      [](hid_t group, const char* name, const H5A_info_t*, void* data) -> herr_t {
        const hid_t a = H5Aopen(group, name, H5P_DEFAULT);
        const hid_t t = H5Aget_type(a);
        EXPECT_EQ(H5Tget_class(t), H5T_FLOAT) << name;
        H5Tclose(t);
        H5Aclose(a);
        static_cast<std::vector<std::string>*>(data)->push_back(name);
        return 0;
      },
      &names);
  H5Gclose(group);
  EXPECT_EQ(names.size(), outcome_.metrics.size());
  for (const auto& [name, value] : outcome_.metrics) {
    EXPECT_TRUE(H5Aexists_by_name(file, "/metrics/units", name.c_str(), H5P_DEFAULT) > 0) << name;
  }
  H5Fclose(file);
  // friedman1's target is dimensionless: every unit is "1".
  const RunRecord r = read_result(outcome_.result_file);
  EXPECT_EQ(r.metric_units.at("test.mse"), "1");
  EXPECT_EQ(r.metric_units.at("train.r2"), "1");
}

// Files written before /metrics/units kept a `units` text among the metrics:
// still read, the text not taken for a metric, the units derived.
TEST_F(ResultFile, OlderMetricsLayoutStillReads) {
  const auto older = dir_ / "older.h5";
  std::filesystem::copy_file(outcome_.result_file, older);
  const hid_t f = H5Fopen(older.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(H5Ldelete(f, "/metrics/units", H5P_DEFAULT), 0);
  const hid_t type = H5Tcopy(H5T_C_S1);
  H5Tset_size(type, 2);
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a =
      H5Acreate_by_name(f, "/metrics", "units", type, space, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, type, "1");
  H5Aclose(a);
  H5Sclose(space);
  H5Tclose(type);
  H5Fclose(f);
  const RunRecord r = read_result(older);
  EXPECT_EQ(r.metrics, outcome_.metrics);
  EXPECT_EQ(r.metric_units.at("test.rmse"), "1");
  EXPECT_TRUE(r.warnings.empty());
}

// A network that provably predicts a constant (no training
// step, every weight 0: each output is its bias, whatever the input) is a
// complete result with the warning; an ordinary one has none (and no
// `warnings` attribute, like files written before warnings existed).
TEST_F(ResultFile, ConstantNetworkIsCompleteButWarned) {
  RunOptions o;
  o.results_dir = dir_ / "results";
  o.datasets_dir = dir_ / "datasets";
  const LoadedExperiment dead = parse_experiment(
      R"(name: dead
seed: 5
dataset: {generator: friedman1, options: {samples: 120, inputs: 6, noise_std: 0.5}}
model: {hidden: [8], hidden_activation: tanh, init: {weights: {type: normal, mean: 0, std: 0}}}
trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 8, epochs: 0}
)",
      "dead.yaml");
  const RunOutcome out = run_experiment(dead, o);
  ASSERT_TRUE(out.ok) << out.message;
  EXPECT_EQ(out.warnings, std::vector<std::string>{"constant predictions"});
  const RunRecord r = read_result(out.result_file);
  EXPECT_EQ(r.provenance.status, "complete");
  EXPECT_EQ(r.warnings, std::vector<std::string>{"constant predictions"});
  // Independently: every stored test prediction equals the first.
  EXPECT_EQ(r.test_predictions.minCoeff(), r.test_predictions.maxCoeff());
  std::ostringstream shown;
  print_result(r, shown);
  EXPECT_NE(shown.str().find("status       complete; warning: constant predictions"),
            std::string::npos)
      << shown.str();
  EXPECT_EQ(read_result_status(out.result_file).warnings, r.warnings);

  EXPECT_TRUE(outcome_.warnings.empty());
  EXPECT_TRUE(read_result(outcome_.result_file).warnings.empty());
  const hid_t f = H5Fopen(outcome_.result_file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  EXPECT_EQ(H5Aexists(f, "warnings"), 0);
  H5Fclose(f);
}

}  // namespace
}  // namespace cnclab
