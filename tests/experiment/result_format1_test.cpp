// Result files of format 1 (before metrics per split): a result the runner
// wrote, turned into what the code of then wrote through the raw HDF5 C API
// (root format_version 1; the test split's metrics under their bare names,
// normalised_mse of the test split, normalised_validation_mse; no
// /metrics/units). Read back, they carry today's names (format1_metric_name,
// the one place that maps them) with the same numbers; the result store
// never reuses them for a new run.
#include <gtest/gtest.h>
#include <hdf5.h>

#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/experiment/runner.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const char* kFormat1Yaml = R"(name: tiny
seed: 5
dataset: {generator: friedman1, options: {samples: 100, inputs: 5, noise_std: 0.5}}
split: {train: 0.6, validation: 0.2}
model: {hidden: [4], hidden_activation: tanh}
trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, batch_size: 8, epochs: 2}
metrics: [mse, rmse, mae, max_abs_error, r2, normalised_mse]
)";

void set_double(hid_t loc, const std::string& name, double v) {
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(loc, name.c_str(), H5T_IEEE_F64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_DOUBLE, &v);
  H5Aclose(a);
  H5Sclose(space);
}

// `file` rewritten as result format 1 with `old_metrics` as its /metrics.
void make_format1(const fs::path& file, const std::map<std::string, double>& old_metrics) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  ASSERT_GE(H5Adelete(f, "format_version"), 0);
  const std::int64_t one = 1;
  const hid_t space = H5Screate(H5S_SCALAR);
  const hid_t a = H5Acreate2(f, "format_version", H5T_STD_I64LE, space, H5P_DEFAULT, H5P_DEFAULT);
  H5Awrite(a, H5T_NATIVE_INT64, &one);
  H5Aclose(a);
  H5Sclose(space);
  ASSERT_GE(H5Ldelete(f, "/metrics", H5P_DEFAULT), 0);
  const hid_t g = H5Gcreate2(f, "/metrics", H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT);
  for (const auto& [name, value] : old_metrics) set_double(g, name, value);
  H5Gclose(g);
  H5Fclose(f);
}

class Format1 : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_ / "tiny.yaml") << kFormat1Yaml;
    RunOptions o;
    o.results_dir = dir_ / "results";
    o.datasets_dir = dir_ / "datasets";
    outcome_ = run_experiment(load_experiment(dir_ / "tiny.yaml"), o);
    ASSERT_TRUE(outcome_.ok) << outcome_.message;
    // What format 1 stored of this run: the test split's metrics and the
    // validation split's normalised MSE.
    const auto& m = outcome_.metrics;
    for (const char* base : {"mse", "rmse", "mae", "max_abs_error", "r2", "normalised_mse"}) {
      old_[base] = m.at(std::string("test.") + base);
      expected_[std::string("test.") + base] = old_[base];
    }
    old_["normalised_validation_mse"] = m.at("validation.normalised_mse");
    expected_["validation.normalised_mse"] = old_["normalised_validation_mse"];
  }
  TempDir dir_;
  RunOutcome outcome_;
  std::map<std::string, double> old_, expected_;
};

// The run stored every metric on every split, under <split>.<name>.
TEST_F(Format1, TodaysRunStoresEverySplit) {
  EXPECT_EQ(outcome_.metrics.size(), 18u);  // 6 metrics x train, validation, test
  for (const char* split : {"train.", "validation.", "test."}) {
    EXPECT_TRUE(outcome_.metrics.contains(std::string(split) + "rmse")) << split;
  }
  EXPECT_EQ(read_result(outcome_.result_file).format_version, kResultFormatVersion);
}

TEST_F(Format1, OlderNamesReadAsTodaysWithTheSameNumbers) {
  const fs::path old = dir_ / "old.h5";
  fs::copy_file(outcome_.result_file, old);
  make_format1(old, old_);
  const RunRecord r = read_result(old);
  EXPECT_EQ(r.format_version, 1);
  EXPECT_EQ(r.metrics, expected_);
  // No /metrics/units in those files: derived from the targets (friedman1: "1").
  EXPECT_EQ(r.metric_units.at("test.mse"), "1");
  EXPECT_EQ(r.metric_units.at("validation.normalised_mse"), "scaled²");
  EXPECT_EQ(read_result_status(old).metrics, expected_);
  std::ostringstream shown;
  print_result(r, shown);
  EXPECT_NE(shown.str().find("an older result (format 1)"), std::string::npos) << shown.str();
  EXPECT_NE(shown.str().find("  validation.normalised_mse"), std::string::npos) << shown.str();
  EXPECT_EQ(shown.str().find("  rmse "), std::string::npos) << shown.str();
}

// At the store's path of its config (a result of an older cnclab), a format-1
// training result is not reused: it lacks the per-split metrics choices need.
TEST_F(Format1, StoreDoesNotReuseIt) {
  make_format1(outcome_.result_file, old_);
  const ResultStore store(dir_ / "results");
  const LoadedExperiment e = load_experiment(dir_ / "tiny.yaml");
  try {
    store.existing(result_key(e));
    FAIL() << "a format-1 result was reused";
  } catch (const OutdatedResult& err) {
    EXPECT_NE(std::string(err.what()).find("result format 1"), std::string::npos) << err.what();
  }
  EXPECT_THROW(store.get(e), MissingResults);
}

// A job result of format 1 keeps its own metric names; only the training
// metrics it carries (a sweep job's selected trial's) get today's names.
TEST(Format1Names, JobResultsRenameOnlyTheTrainingMetricsTheyCarry) {
  TempDir dir;
  RunRecord job =
      make_job_record("sweep", {"search", std::nullopt, "name: search\n", {}, false}, {});
  job.metrics = {{"rmse", 1.0}};  // replaced below by the format-1 layout
  const fs::path file = dir / "job.h5";
  write_job_result(file, job);
  make_format1(file, {{"rmse", 1.5},
                      {"normalised_validation_mse", 0.25},
                      {"sweep.trials", 3},
                      {"points", 7},
                      {"wall_seconds", 2}});
  const RunRecord r = read_result(file);
  EXPECT_EQ(r.kind, "sweep");
  EXPECT_EQ(r.format_version, 1);
  EXPECT_EQ(r.metrics, (std::map<std::string, double>{{"test.rmse", 1.5},
                                                      {"validation.normalised_mse", 0.25},
                                                      {"sweep.trials", 3},
                                                      {"points", 7},
                                                      {"wall_seconds", 2}}));
}

TEST(Format1Names, EachOlderNameHasOneNewName) {
  EXPECT_EQ(format1_metric_name("rmse"), "test.rmse");
  EXPECT_EQ(format1_metric_name("r2"), "test.r2");
  EXPECT_EQ(format1_metric_name("normalised_mse"), "test.normalised_mse");
  EXPECT_EQ(format1_metric_name("normalised_validation_mse"), "validation.normalised_mse");
  // A narx run's registered metrics were of its validation half.
  EXPECT_EQ(format1_metric_name("closed_loop_rms_x"), "validation.closed_loop_rms_x");
  EXPECT_EQ(format1_metric_name("contour_rms"), "validation.contour_rms");
  // Today's names stay.
  EXPECT_EQ(format1_metric_name("validation.rmse"), "validation.rmse");
}

}  // namespace
}  // namespace cnclab
