// `cnclab predict` and `cnclab export` on bad input: exit 2, the reason on
// stderr, nothing written. And what a good OUT carries: the result's
// identity and the input's hash, for each kind of input.
#include <gtest/gtest.h>

#include <fstream>

#include "cnclab/data/dataset_file.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/h5.hpp"
#include "common/temp_dir.hpp"
#include "deploy/deploy_fixtures.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

const std::string kFriedman = CNCLAB_SOURCE_DIR
    "/experiments/friedman/friedman1_mlp.yaml dataset.options.samples=200 trainer.epochs=2";

class DeployBadInput : public ::testing::Test {
 protected:
  void SetUp() override { result_ = testing::train(dir_.path(), kFriedman); }

  // Runs `args`; expects exit 2 with `reason` on stderr and no `out`.
  void expect_refused(const std::string& args, const std::string& reason,
                      const std::string& out = "out.csv") {
    const auto r = testing::cnclab(dir_.path(), args);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err << r.out;
    EXPECT_NE(r.err.find(reason), std::string::npos) << args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / out)) << args;
  }
  void csv(const std::string& text) { std::ofstream(dir_ / "in.csv") << text; }

  TempDir dir_;
  std::string result_;
};

TEST_F(DeployBadInput, PredictRefusesBadInputsAndWritesNothing) {
  const std::string predict = "predict " + result_ + " in.csv -o out.csv";
  csv("x1,x2,x3\n1,2,3\n");
  expect_refused(predict, "the network reads 10 input columns");
  csv("x1,x2,x3,x4,x5,x6,x7,x8,x9,x10\n1,2,3,4,5,6,7,8,nan,1\n");
  expect_refused(predict, "in.csv:2 column 9 (x9): nan (NaN or infinity)");
  csv("x1,x2,x3,x4,x5,x6,x7,x8,x9,x10\n1,2,3,4,5,6,7,8,9,inf\n");
  expect_refused(predict, "(NaN or infinity)");
  csv("");
  expect_refused(predict, "in.csv: empty file");
  csv("x1,x2,x3,x4,x5,x6,x7,x8,x9,x10\n");
  expect_refused(predict, "no rows of values");
  csv("x1,x2,x3,x4,x5,x6,x7,x8,x9,x10,x11\n1,2,3,4,5,6,7,8,9,1,0\n");
  expect_refused(predict, "column 'x11' is not one the network reads");
  csv("x1 [mm],x2,x3,x4,x5,x6,x7,x8,x9,x10\n1,2,3,4,5,6,7,8,9,1\n");
  expect_refused(predict, "column x1 is in mm, the network reads it in 1");
  csv("x1,x2,x3,x4,x5,x6,x7,x8,x9,x10\n1,2,3,4,5,6,7,8,9,1\n");
  expect_refused(predict + " --split test", "is not the result's training dataset");
  expect_refused(predict + " --split half", "must be all, train, validation or test");
  expect_refused(predict + " --initial rest", "--initial: a narx option");
  expect_refused(predict + " dataset.options.samples=3", "apply to a dataset config (.yaml) only");
  expect_refused("predict " + result_ + " in.csv -o out.txt", "the output is a .h5 or a .csv",
                 "out.txt");
  expect_refused("predict " + result_ + " missing.csv -o out.csv", "missing.csv: no such file");
  expect_refused("predict " + result_ + " in.json -o out.csv", "unknown input");

  // A dataset of another generator.
  const auto gen = testing::cnclab(
      dir_.path(), "dataset generate " CNCLAB_SOURCE_DIR
                   "/experiments/ik/ik_x.yaml dataset.options.values_per_input=2 --out ik.h5 -q");
  ASSERT_EQ(gen.code, 0) << gen.err;
  expect_refused("predict " + result_ + " ik.h5 -o out.csv",
                 "a dataset of generator ik_samples; the network was trained on friedman1");
}

TEST_F(DeployBadInput, FailedAndJobResultsHaveNoNetworkToUse) {
  const auto run =
      testing::cnclab(dir_.path(), "run " + kFriedman +
                                       " name=diverged trainer.learning_rate=1e12 trainer.epochs=5"
                                       " --out results --quiet");
  ASSERT_EQ(run.code, 1) << run.err << run.out;
  const std::string marker = "result (status failed): ";
  const auto at = run.out.find(marker);
  ASSERT_NE(at, std::string::npos) << run.out;
  const std::string diverged =
      run.out.substr(at + marker.size(), run.out.find('\n', at) - at - marker.size());
  csv("x1,x2,x3,x4,x5,x6,x7,x8,x9,x10\n1,2,3,4,5,6,7,8,9,1\n");
  expect_refused("predict " + diverged + " in.csv -o out.csv", "its training failed");
  expect_refused("export " + diverged + " --format c -o c", "its training failed", "c");

  const auto job =
      testing::cnclab(dir_.path(), "run " CNCLAB_SOURCE_DIR
                                   "/experiments/trochoid/groove_table2.yaml --out results");
  ASSERT_EQ(job.code, 0) << job.err;
  std::string job_result;
  for (const auto& e :
       fs::recursive_directory_iterator(dir_ / "results" / "trochoid_groove_table2")) {
    if (e.path().extension() == ".h5") job_result = fs::relative(e.path(), dir_.path()).string();
  }
  ASSERT_FALSE(job_result.empty());
  expect_refused("predict " + job_result + " in.csv -o out.csv", "not a trained network");
  expect_refused("export " + job_result + " -o c", "not a trained network", "c");
}

TEST_F(DeployBadInput, ExportRefusesUnknownFormatsPrecisionsAndNames) {
  const std::string exp = "export " + result_ + " -o c";
  expect_refused(exp + " --format onnx", "--format onnx: must be c", "c");
  expect_refused(exp + " --precision half", "--precision half: must be float or double", "c");
  expect_refused(exp + " --format torch --precision float", "--precision is for --format c", "c");
  expect_refused(exp + " --name 1model", "--name 1model: must not start with a digit", "c");
  expect_refused(exp + " --name static", "is a C keyword", "c");
}

TEST_F(DeployBadInput, OutCarriesTheResultsIdentityAndTheInputsHash) {
  const RunRecord rec = read_result(dir_ / result_);
  const std::string identity = result_identity(rec);
  // A dataset file: its content hash.
  auto r = testing::cnclab(
      dir_.path(), "predict " + result_ + " " + rec.dataset_file + " -o all.h5 --data-dir data");
  ASSERT_EQ(r.code, 0) << r.err;
  const H5File f = H5File::open_read(dir_ / "all.h5");
  EXPECT_EQ(f.attribute_string("/provenance", "result_identity"), identity);
  EXPECT_EQ(f.attribute_string("/provenance", "input_hash"), rec.dataset_hash);
  EXPECT_EQ(f.attribute_string("/provenance", "input_kind"), "dataset");
  EXPECT_EQ(f.read_vector("/predictions/y.predicted").size(), 200u);
  EXPECT_EQ(f.units("/predictions/y.predicted"), "1");
  // A config, generated on the fly (another seed: other samples).
  r = testing::cnclab(dir_.path(), "predict " + result_ +
                                       " " CNCLAB_SOURCE_DIR
                                       "/experiments/friedman/friedman1_mlp.yaml "
                                       "dataset.options.samples=50 dataset.seed=9 -o cfg.csv "
                                       "--data-dir data -q");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = testing::slurp(dir_ / "cfg.csv");
  EXPECT_NE(text.find("# result_identity: " + identity), std::string::npos) << text;
  EXPECT_NE(text.find("# input_kind: dataset config"), std::string::npos) << text;
  EXPECT_NE(text.find("sample [1],y.predicted [1],y.measured [1]"), std::string::npos) << text;
  // A CSV: the hash of its bytes changes with them.
  csv("x1,x2,x3,x4,x5,x6,x7,x8,x9,x10\n1,2,3,4,5,6,7,8,9,1\n");
  ASSERT_EQ(testing::cnclab(dir_.path(), "predict " + result_ + " in.csv -o a.csv").code, 0);
  csv("x1,x2,x3,x4,x5,x6,x7,x8,x9,x10\n1,2,3,4,5,6,7,8,9,2\n");
  ASSERT_EQ(testing::cnclab(dir_.path(), "predict " + result_ + " in.csv -o b.csv").code, 0);
  const auto hash_line = [&](const std::string& file) {
    const std::string t = testing::slurp(dir_ / file);
    const auto at = t.find("# input_hash: ");
    return t.substr(at, t.find('\n', at) - at);
  };
  EXPECT_NE(hash_line("a.csv"), hash_line("b.csv"));
}

}  // namespace
}  // namespace cnclab
