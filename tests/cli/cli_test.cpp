// End-to-end tests of the `cnclab` executable: exit codes, one-line errors,
// nothing written on bad input, complete results read back by h5dump/h5diff
// (independent tools from hdf5-tools).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/process.hpp"

namespace {
namespace fs = std::filesystem;

const std::string kCnclab = CNCLAB_BINARY_DIR "/cnclab";
const std::string kExperiment = CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_mlp.yaml";

using Result = cnclab::testing::ShellResult;
using cnclab::testing::slurp;

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("cnclab_cli_test_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Runs a shell command line in dir_ with stdout/stderr captured.
  Result sh(const std::string& command) const { return cnclab::testing::run_shell(dir_, command); }
  Result cnclab(const std::string& args) const { return sh(kCnclab + " " + args); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return dir_ / name;
  }
  // Everything in dir_ except the files the test wrote itself.
  std::vector<fs::path> outputs() const {
    std::vector<fs::path> out;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) {
      if (e.is_regular_file() && e.path().extension() != ".yaml" &&
          e.path().extension() != ".h5bad") {
        out.push_back(e.path());
      }
    }
    return out;
  }
  // A fast variant of the friedman experiment.
  std::string quick(const std::string& extra = "") const {
    return "run " + kExperiment + " trainer.epochs=3 dataset.options.samples=200 --quiet " + extra;
  }

  fs::path dir_;
};

void expect_one_line_error(const Result& r, int code, const std::string& fragment) {
  EXPECT_EQ(r.code, code) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(Cli, UnknownKeyIsUsageErrorAndWritesNothing) {
  expect_one_line_error(cnclab(quick("trainer.momentm=0.5")), 2,
                        "trainer.momentm: unknown key (did you mean 'momentum'?)");
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, TypoInNestedKeyInFileNamesFileLineAndKey) {
  const auto file = write(
      "typo.yaml", "include: " + kExperiment + "\nmodel:\n  dropout:\n    keep_probabilty: 0.5\n");
  expect_one_line_error(cnclab("run " + file.string() + " --quiet"), 2,
                        file.string() + ":4:22: model.dropout.keep_probabilty: unknown key");
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, WrongTypeIsUsageError) {
  expect_one_line_error(cnclab(quick("trainer.epochs=many")), 2,
                        "trainer.epochs = many: expected a non-negative integer");
}

// An experiment whose dataset include was forgotten trains
// on nothing: exit 2 naming the missing key and the fragments that provide it,
// and no result written.
TEST_F(Cli, ExperimentWithoutDatasetIsUsageErrorNamingTheFragments) {
  const fs::path file =
      write("nodata.yaml", "name: nodata\nseed: 1\ninclude: " CNCLAB_SOURCE_DIR
                           "/configs/trainers/sgdm_minibatch.yaml\nmodel: {hidden: [4]}\n");
  fs::create_directories(dir_ / "configs/datasets");
  write("configs/datasets/surface_a.yaml", "dataset: {generator: step_error}\n");
  expect_one_line_error(cnclab("run " + file.string() + " --quiet"), 2,
                        "nodata.yaml: dataset.generator: is required (what data the experiment "
                        "learns); the fragments in configs/datasets/ provide one (include: "
                        "configs/datasets/NAME.yaml): surface_a.yaml");
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, OutOfRangeNamesValueAndRule) {
  const Result r = cnclab(quick("trainer.momentum=1.5"));
  expect_one_line_error(r, 2, "override trainer.momentum=1.5: trainer.momentum = 1.5:");
  EXPECT_NE(r.err.find("[0, 1)"), std::string::npos) << r.err;
  EXPECT_TRUE(outputs().empty());
}

// CLI11's own errors take the one error form too.
TEST_F(Cli, MissingExperimentFileIsUsageError) {
  expect_one_line_error(cnclab("run does_not_exist.yaml"), 2,
                        "cnclab: error: experiment: File does not exist: does_not_exist.yaml");
  expect_one_line_error(cnclab("run"), 2, "cnclab: error: experiment is required");
  EXPECT_EQ(cnclab("run --help").code, 0);
}

TEST_F(Cli, MalformedYamlNamesPosition) {
  const auto file = write("bad.yaml", "name: x\nseed: [1, 2\n");
  expect_one_line_error(cnclab("validate " + file.string()), 2, file.string() + ":");
  EXPECT_NE(cnclab("validate " + file.string()).err.find("malformed YAML"), std::string::npos);
}

// --seed (run, validate, sweep) and --sweep-seed take what `seed:` in YAML
// takes: 0 to 2^64 - 1. CLI11 alone read "-1" as 2^64 - 1.
TEST_F(Cli, BadSeedsAreUsageErrorsNamingTheValueAndRunNothing) {
  const std::string exp = " " + kExperiment + " trainer.epochs=1 dataset.options.samples=100 ";
  for (const std::string command : {"run", "validate", "sweep"}) {
    for (const std::string seed : {"-1", "1.5", "1e3", "seven", "18446744073709551616"}) {
      const Result r = cnclab(command + exp + "--seed " + seed);
      expect_one_line_error(r, 2, "cnclab: error: --seed " + seed + ": ");
      EXPECT_NE(r.err.find(seed == "18446744073709551616" ? "integer too large"
                                                          : "expected a non-negative integer"),
                std::string::npos)
          << r.err;
    }
  }
  expect_one_line_error(cnclab("sweep" + exp + "trainer.epochs=1,2 --sweep-seed -1"), 2,
                        "cnclab: error: --sweep-seed -1: expected a non-negative integer");
  EXPECT_TRUE(outputs().empty());
  // The largest seed is a seed like any other.
  const Result r = cnclab("validate" + exp + "--seed 18446744073709551615");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("\nseed: 18446744073709551615\n"), std::string::npos) << r.out;
}

// Counts too: CLI11 alone read "--repeats -1" as 2^64 - 1 repeats.
TEST_F(Cli, NegativeOrFractionalCountsAreUsageErrors) {
  for (const std::string& args :
       {"sweep " + kExperiment + " trainer.epochs=1,2 --repeats -1",
        "sweep " + kExperiment + " --trials 1.5",
        "sweep " + kExperiment + " trainer.epochs=1,2 -j -1", std::string("reproduce --jobs -1")}) {
    const Result r = cnclab(args);
    EXPECT_EQ(r.code, 2) << args << r.err;
    EXPECT_NE(r.err.find(": expected a non-negative integer, got "), std::string::npos) << r.err;
  }
  EXPECT_TRUE(outputs().empty());
}

// An experiment copied out of the repository finds the shared configs
// through CNCLAB_CONFIG_PATH or the current directory's configs/, and says
// where it looked when it cannot. build/cnclab also finds them in the source
// tree it was built from (core/share_paths.hpp); a copy of the executable
// outside the build tree, with no share folder beside it, does not (unless
// cnclab is installed in the compiled-in CMAKE_INSTALL_PREFIX).
TEST_F(Cli, CopiedExperimentFindsConfigsThroughTheConfigPathOrSaysWhereItLooked) {
  fs::create_directories(dir_ / "studies");
  fs::copy_file(kExperiment, dir_ / "studies/my.yaml");
  const std::string trainer = "configs/trainers/sgdm_minibatch.yaml";
  fs::create_directories(dir_ / "bin");
  fs::copy_file(kCnclab, dir_ / "bin/cnclab");
  const Result missing = sh((dir_ / "bin/cnclab").string() + " validate studies/my.yaml");
  expect_one_line_error(missing, 2,
                        "studies/my.yaml:8:10: include " + trainer +
                            ": not found; looked in: "
                            "studies/configs/trainers/sgdm_minibatch.yaml (relative to the naming "
                            "file)");
  EXPECT_NE(missing.err.find((dir_ / trainer).string() + " (configs/ of the current directory)"),
            std::string::npos)
      << missing.err;
  EXPECT_NE(missing.err.find("CNCLAB_CONFIG_PATH"), std::string::npos) << missing.err;
  EXPECT_NE(missing.err.find("no cnclab share folder (installed, next to the executable " +
                             (dir_ / "share/cnclab").string() + ": absent"),
            std::string::npos)
      << missing.err;

  const Result via_source = cnclab("validate studies/my.yaml");
  EXPECT_EQ(via_source.code, 0) << via_source.err;
  EXPECT_NE(via_source.out.find("momentum: 0.9"), std::string::npos) << via_source.out;

  const std::string configs = CNCLAB_SOURCE_DIR "/configs";
  const Result via_path = sh("CNCLAB_CONFIG_PATH=/nonexistent:" + configs + " " +
                             (dir_ / "bin/cnclab").string() + " validate studies/my.yaml");
  EXPECT_EQ(via_path.code, 0) << via_path.err;
  EXPECT_NE(via_path.out.find("momentum: 0.9"), std::string::npos) << via_path.out;

  fs::create_directory_symlink(configs, dir_ / "configs");
  const Result via_cwd = sh((dir_ / "bin/cnclab").string() + " validate studies/my.yaml");
  EXPECT_EQ(via_cwd.code, 0) << via_cwd.err;
}

// The host label partial names carry (atomic_file.hpp), worked out here
// from gethostname; "" if it would need sanitising.
std::string plain_host_label() {
  char buffer[256] = {};
  if (::gethostname(buffer, sizeof buffer - 1) != 0) return "";
  std::string label(buffer);
  label = label.substr(0, label.find('.'));
  const bool plain = std::all_of(label.begin(), label.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '-';
  });
  return plain ? label : "";
}

TEST_F(Cli, RunRemovesPartialFilesOfGoneWritersAndKeepsLiveOnes) {
  const std::string host = plain_host_label();
  if (host.empty()) GTEST_SKIP() << "host name needs sanitising";
  const pid_t child = ::fork();
  if (child == 0) ::_exit(0);
  ::waitpid(child, nullptr, 0);
  if (::kill(child, 0) == 0 || errno != ESRCH) GTEST_SKIP() << "pid reused at once";
  const std::string tag = "-0123456789abcdef";
  const fs::path stale =
      dir_ / ("results/friedman1_mlp/.old.h5.partial-" + host + "-" + std::to_string(child) + tag);
  const fs::path live =
      dir_ / ("datasets/.d.h5.partial-" + host + "-" + std::to_string(::getpid()) + tag);
  for (const auto& p : {stale, live}) {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << "partial";
  }
  const Result r = cnclab(quick());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_EQ(r.err, "removed 1 partial file of interrupted writes (writer pid " +
                       std::to_string(child) +
                       " no longer running): " + stale.lexically_relative(dir_).string() + "\n");
}

TEST_F(Cli, CorruptResultGivenToShowFailsCleanly) {
  const auto file = write("corrupt.h5bad", "this is not an HDF5 file\n");
  expect_one_line_error(cnclab("show " + file.string()), 1, file.string());
}

TEST_F(Cli, ValidatePrintsResolvedConfigWithDefaultsAndWritesNothing) {
  const Result r = cnclab("validate " + kExperiment + " trainer.momentum=0.5");
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("momentum: 0.5"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("early_stop_patience: 0"), std::string::npos) << r.out;  // a default
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, TrainbrExperimentValidatesWithMatlabDefaultsAndRuns) {
  const std::string exp = CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_trainbr.yaml";
  Result r = cnclab("validate " + exp);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("type: trainbr"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("mu: 0.005"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("inputs: minmax"), std::string::npos) << r.out;
  // With a validation split trainbr still has no validation stop (MATLAB's
  // trainbr): `run` and `show` say the split is only scored.
  r = cnclab("run " + exp +
             " trainer.epochs=3 dataset.options.samples=120 split.validation=0.2 --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string note =
      "trainbr has no validation stop (as MATLAB's trainbr): the 24 validation samples are held "
      "out of training and only scored (validation.*)";
  EXPECT_NE(r.err.find("note: friedman1_trainbr: " + note), std::string::npos) << r.err;
  const Result shown = cnclab("show results/friedman1_trainbr/*.h5");
  EXPECT_EQ(shown.code, 0) << shown.err;
  EXPECT_NE(shown.out.find("gamma "), std::string::npos) << shown.out;
  EXPECT_NE(shown.out.find("validation   " + note), std::string::npos) << shown.out;
  expect_one_line_error(cnclab("run " + exp + " trainer.type=rprop --quiet"), 2,
                        "trainer.type = rprop: must be one of: sgdm, lm, trainbr");
  expect_one_line_error(cnclab("run " + exp + " trainer.mu_dec=2 --quiet"), 2,
                        "trainer.mu_dec = 2: must be in (0, 1)");
}

TEST_F(Cli, HelpExplainsWithExample) {
  for (const char* sub : {"run", "validate", "show", "reproduce", "sweep", "sweep merge", "compare",
                          "version", "init"}) {
    const Result r = cnclab(std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("Example"), std::string::npos) << sub << r.out;
  }
  EXPECT_EQ(cnclab("").code, 2);
  EXPECT_EQ(cnclab("frobnicate").code, 2);
}

TEST_F(Cli, RunWritesCompleteResultReadableByShowAndH5dump) {
  const Result r = cnclab(quick());
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path file = dir_ / r.out.substr(0, r.out.find('\n'));
  ASSERT_TRUE(fs::exists(file)) << r.out;
  EXPECT_EQ(file.parent_path().filename(), "friedman1_mlp");
  // No temporary left behind.
  for (const auto& e : fs::directory_iterator(file.parent_path())) {
    EXPECT_EQ(e.path().filename().string().find(".partial"), std::string::npos);
  }
  const Result show = cnclab("show " + file.string());
  EXPECT_EQ(show.code, 0) << show.err;
  EXPECT_NE(show.out.find("complete"), std::string::npos) << show.out;
  EXPECT_NE(show.out.find("  validation.rmse "), std::string::npos) << show.out;
  EXPECT_NE(show.out.find("  test.rmse "), std::string::npos) << show.out;
  // h5dump (independent reader) sees the metric attributes and units.
  const Result dump = sh("h5dump -A '" + file.string() + "'");
  EXPECT_EQ(dump.code, 0) << dump.err;
  EXPECT_NE(dump.out.find("\"units\""), std::string::npos);
  EXPECT_NE(dump.out.find("\"test.rmse\""), std::string::npos);
}

// An inlined NURBS surface (step-error datasets) prints as
// shapes and hashes in `validate` and `show`; --full prints it all, and that
// text is an experiment that resolves to the same config.
TEST_F(Cli, ValidateAndShowAbbreviateLargeArraysFullPrintsThem) {
  const std::string exp = CNCLAB_SOURCE_DIR "/experiments/step_error/surface1.yaml";
  const std::string small = " dataset.options.lines=4 dataset.options.points_per_line=6 ";
  const Result brief = cnclab("validate " + exp + small);
  ASSERT_EQ(brief.code, 0) << brief.err;
  EXPECT_NE(brief.out.find("control_points: 16 × 16 × 3, hash "), std::string::npos) << brief.out;
  EXPECT_NE(brief.out.find("knots_u: 20 values, hash "), std::string::npos) << brief.out;
  EXPECT_NE(brief.out.find("--full prints them"), std::string::npos) << brief.out;
  const Result full = cnclab("validate " + exp + small + "--full");
  ASSERT_EQ(full.code, 0) << full.err;
  EXPECT_EQ(full.out.find(", hash "), std::string::npos);
  EXPECT_GT(std::count(full.out.begin(), full.out.end(), '\n'),
            std::count(brief.out.begin(), brief.out.end(), '\n') + 30);
  write("full.yaml", full.out);
  const Result again = cnclab("validate full.yaml --full");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(again.out.substr(again.out.find('\n')), full.out.substr(full.out.find('\n')));

  const Result r = cnclab("run " + exp + small + "trainer.epochs=1 --quiet --out r --data-dir d");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string file = r.out.substr(0, r.out.find('\n'));
  const Result shown = cnclab("show " + file);
  ASSERT_EQ(shown.code, 0) << shown.err;
  EXPECT_NE(shown.out.find("control_points: 16 × 16 × 3, hash "), std::string::npos) << shown.out;
  // Provenance, config and metrics per split take about 85 lines; the 16 × 16
  // control points alone would add 256.
  EXPECT_LT(std::count(shown.out.begin(), shown.out.end(), '\n'), 120) << shown.out;
  const Result shown_full = cnclab("show --full " + file);
  EXPECT_EQ(shown_full.out.find("control_points: 16"), std::string::npos) << shown_full.out;
  EXPECT_NE(shown_full.out.find("control_points:\n"), std::string::npos) << shown_full.out;
  // Each metric with its own unit (step error: µm), on each split.
  for (const char* line : {"  test.mse ", "  test.rmse ", "  train.r2 "}) {
    const auto at = shown.out.find(line);
    ASSERT_NE(at, std::string::npos) << line << shown.out;
    const std::string text = shown.out.substr(at, shown.out.find('\n', at) - at);
    const std::string unit = std::string(line) == "  test.mse "    ? "µm²"
                             : std::string(line) == "  test.rmse " ? "µm"
                                                                   : "1 (dimensionless)";
    EXPECT_EQ(text.substr(text.size() - unit.size()), unit) << text;
  }
  EXPECT_EQ(shown.out.find("(test split, µm)"), std::string::npos) << shown.out;
}

// A network that provably predicts a constant (no training
// step, all weights 0) is complete, and `run`, `show`, `compare` and
// `reproduce` say "constant predictions".
TEST_F(Cli, ConstantNetworkIsWarnedInRunShowCompareAndReproduce) {
  write("dead.yaml", "include: " + kExperiment +
                         "\nname: dead\ndataset: {options: {samples: 200}}\ntrainer: {epochs: "
                         "0}\nmodel: {init: {weights: {type: normal, mean: 0, std: 0}}}\n");
  const Result dead = cnclab("run dead.yaml --out r --data-dir d");
  ASSERT_EQ(dead.code, 0) << dead.err;
  EXPECT_NE(dead.err.find("warning: dead: constant predictions"), std::string::npos) << dead.err;
  const std::string file = dead.out.substr(dead.out.find('\n') + 1);
  const std::string dead_file = file.substr(0, file.find('\n'));
  const Result shown = cnclab("show " + dead_file);
  EXPECT_NE(shown.out.find("status       complete; warning: constant predictions"),
            std::string::npos)
      << shown.out;
  const Result alive = cnclab(quick("--out r --data-dir d"));
  ASSERT_EQ(alive.code, 0) << alive.err;
  EXPECT_EQ(alive.err.find("constant predictions"), std::string::npos) << alive.err;
  const Result compared =
      cnclab("compare " + alive.out.substr(0, alive.out.find('\n')) + " " + dead_file);
  ASSERT_EQ(compared.code, 0) << compared.err;
  EXPECT_NE(compared.out.find("complete; warning: constant predictions"), std::string::npos)
      << compared.out;
  const Result reproduced = cnclab("reproduce dead.yaml --out r --data-dir d --jobs 1");
  ASSERT_EQ(reproduced.code, 0) << reproduced.err;
  EXPECT_NE(reproduced.out.find("WARNING constant predictions; train: mae "), std::string::npos)
      << reproduced.out;
}

TEST_F(Cli, SameSeedGivesIdenticalResultApartFromProvenance) {
  // The second run reuses the cached dataset the first one wrote.
  const Result a = cnclab(quick("--out a --data-dir d"));
  const Result b = cnclab(quick("--out b --data-dir d"));
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  const std::string fa = a.out.substr(0, a.out.find('\n'));
  const std::string fb = b.out.substr(0, b.out.find('\n'));
  EXPECT_EQ(fs::path(fa).filename(), fs::path(fb).filename());
  // h5diff exits 0 only when every object and attribute is identical.
  // Times live in /provenance and /history/wall_seconds only.
  const std::string exclude = " --exclude-path /provenance --exclude-path /history/wall_seconds ";
  const Result diff = sh("h5diff" + exclude + fa + " " + fb);
  EXPECT_EQ(diff.code, 0) << diff.out << diff.err;
  // A different seed changes the result.
  const Result c = cnclab(quick("--out c --data-dir d --seed 7"));
  ASSERT_EQ(c.code, 0) << c.err;
  const std::string fc = c.out.substr(0, c.out.find('\n'));
  EXPECT_NE(sh("h5diff -q" + exclude + fa + " " + fc).code, 0);
}

TEST_F(Cli, DivergedTrainingIsAFailedResultNotACrash) {
  // 120 training samples: 12 batches in 3 epochs; 1e20 overflows within them.
  const Result r = cnclab(quick("trainer.learning_rate=1e20"));
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("FAILED"), std::string::npos) << r.out;
  const std::string file =
      r.out.substr(r.out.rfind(": ") + 2, r.out.size() - r.out.rfind(": ") - 3);
  const Result show = cnclab("show " + file);
  EXPECT_EQ(show.code, 0) << show.err;
  EXPECT_NE(show.out.find("failed"), std::string::npos) << show.out;
}

// A small step-error config: 3 lines x 5 CC points on surface 1.
std::string step_error_config() {
  return "dataset:\n  generator: step_error\n  options:\n    surface: " CNCLAB_SOURCE_DIR
         "/configs/surfaces/surface1.yaml\n    lines: 3\n    points_per_line: 5\n";
}

TEST_F(Cli, DatasetGenerateWritesAFileThatShowDescribes) {
  write("s1.yaml", step_error_config());
  const Result g = cnclab("dataset generate s1.yaml --out out/s1.h5");
  ASSERT_EQ(g.code, 0) << g.err;
  EXPECT_NE(g.out.find("wrote out/s1.h5: 12 samples, 73 inputs, 1 targets"), std::string::npos)
      << g.out;
  const Result show = cnclab("dataset show out/s1.h5");
  ASSERT_EQ(show.code, 0) << show.err;
  for (const char* text :
       {"samples    12", "inputs     73", "p20_z", "cl_i+1_x", "mm", "step_error", "µm",
        "histogram of step_error [µm]", "convex/concave split: convex", "u_i+1"}) {
    EXPECT_NE(show.out.find(text), std::string::npos) << text << "\n" << show.out;
  }
  // h5dump (independent reader) sees the metadata beside the inputs, with units.
  const Result dump = sh("h5dump -A out/s1.h5");
  EXPECT_NE(dump.out.find("DATASET \"metadata\""), std::string::npos) << dump.out;
  EXPECT_NE(dump.out.find("( 12, 9 )"), std::string::npos) << dump.out;
  // Default output name and overrides.
  const Result d = cnclab("dataset generate s1.yaml dataset.options.lines=2");
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_NE(d.out.find("wrote datasets/s1.h5: 8 samples"), std::string::npos) << d.out;
  EXPECT_TRUE(fs::exists(dir_ / "datasets" / "s1.h5"));
  // dataset.targets keeps those targets, in that order, as a run would.
  const Result ik = cnclab("dataset generate " CNCLAB_SOURCE_DIR
                           "/configs/studies/ik_table5.yaml dataset.options.values_per_input=2 "
                           "\"dataset.targets=[C, X]\" --out ik.h5 --quiet");
  ASSERT_EQ(ik.code, 0) << ik.err;
  EXPECT_NE(ik.out.find("wrote ik.h5: 32 samples, 5 inputs, 2 targets"), std::string::npos)
      << ik.out;
  EXPECT_EQ(ik.err, "");
  const Result ik_show = cnclab("dataset show ik.h5");
  EXPECT_LT(ik_show.out.find(" C "), ik_show.out.find(" X ")) << ik_show.out;
}

TEST_F(Cli, DatasetGenerateRejectsBadConfigsAndWritesNothing) {
  write("s1.yaml", step_error_config());
  expect_one_line_error(cnclab("dataset generate s1.yaml dataset.options.tool_radius=-1"), 2,
                        "dataset.options.tool_radius = -1: must be a finite ball radius > 0 mm");
  expect_one_line_error(cnclab("dataset generate s1.yaml dataset.options.points_per_line=1"), 2,
                        "points_per_line = 1");
  write("missing.yaml",
        "dataset:\n  generator: step_error\n  options:\n    surface: nowhere.yaml\n");
  expect_one_line_error(cnclab("dataset generate missing.yaml"), 2,
                        "surface = nowhere.yaml: not found; looked in: nowhere.yaml");
  write("nodata.yaml", "name: x\n");
  expect_one_line_error(cnclab("dataset generate nodata.yaml"), 2, "dataset: is required");
  EXPECT_TRUE(outputs().empty());
  const auto corrupt = write("corrupt.h5bad", "not HDF5\n");
  expect_one_line_error(cnclab("dataset show " + corrupt.string()), 1, corrupt.string());
  for (const char* sub : {"dataset", "dataset generate", "dataset show"}) {
    const Result r = cnclab(std::string(sub) + " --help");
    EXPECT_EQ(r.code, 0) << sub;
    EXPECT_NE(r.out.find("Example"), std::string::npos) << sub << r.out;
  }
  EXPECT_EQ(cnclab("dataset").code, 2);
}

TEST_F(Cli, ReproduceRunsAFolderAndPrintsMetrics) {
  fs::create_directories(dir_ / "exps");
  write("exps/e.yaml",
        "include: " + kExperiment + "\ntrainer: {epochs: 2}\ndataset: {options: {samples: 100}}\n");
  const Result r = cnclab("reproduce exps --quiet");
  EXPECT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("friedman1_mlp"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("r2"), std::string::npos) << r.out;
}

// A folder holding OPT_IN.md (an opt-in set, too long for README command
// 1) is skipped by `reproduce` of a folder above it and run when named.
TEST_F(Cli, ReproduceSkipsAnOptInSetUnlessNamed) {
  fs::create_directories(dir_ / "exps/long");
  const std::string tiny =
      "include: " + kExperiment + "\ntrainer: {epochs: 1}\ndataset: {options: {samples: 100}}\n";
  write("exps/e.yaml", tiny + "name: everyday\n");
  write("exps/long/l.yaml", tiny + "name: long_study\n");
  write("exps/long/OPT_IN.md", "run with: cnclab reproduce exps/long\n");
  const Result all = cnclab("reproduce exps --quiet");
  ASSERT_EQ(all.code, 0) << all.err << all.out;
  EXPECT_NE(all.out.find("everyday"), std::string::npos) << all.out;
  EXPECT_EQ(all.out.find("long_study"), std::string::npos) << all.out;
  const Result named = cnclab("reproduce exps/long --quiet");
  ASSERT_EQ(named.code, 0) << named.err << named.out;
  EXPECT_NE(named.out.find("long_study"), std::string::npos) << named.out;
  EXPECT_EQ(named.out.find("everyday"), std::string::npos) << named.out;
}

// `reproduce --quick`: each file's `profiles: {quick: ...}` applies, also to
// the upstream an init_from names, and results go to results/quick.
TEST_F(Cli, QuickProfileAppliesThroughTheGraphIntoItsOwnFolder) {
  fs::create_directories(dir_ / "exps");
  write("exps/up.yaml", "include: " + kExperiment +
                            "\nname: up\ntrainer: {epochs: 4}\ndataset: {options: {samples: 100}}\n"
                            "profiles:\n  quick: {trainer.epochs: 1}\n");
  write("exps/down.yaml",
        "include: up.yaml\nname: down\ninit_from: {experiment: up.yaml}\n"
        "profiles:\n  quick: {trainer.epochs: 2}\n");
  const Result v = cnclab("validate exps/down.yaml --profile quick");
  ASSERT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.out.find("epochs: 2"), std::string::npos) << v.out;
  EXPECT_EQ(v.out.find("profiles"), std::string::npos) << v.out;

  const Result r = cnclab("reproduce exps --quick --quiet");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "results/up"));
  ASSERT_TRUE(fs::is_directory(dir_ / "results/quick/up")) << r.out;
  ASSERT_TRUE(fs::is_directory(dir_ / "results/quick/down")) << r.out;
  for (const char* name : {"up", "down"}) {
    const fs::path folder = dir_ / "results/quick" / name;
    const fs::path file = fs::directory_iterator(folder)->path();
    const Result show = cnclab("show '" + file.string() + "'");
    ASSERT_EQ(show.code, 0) << show.err;
    EXPECT_NE(show.out.find(std::string("epochs: ") + (name == std::string("up") ? "1" : "2")),
              std::string::npos)
        << show.out;
  }
  // A second quick run reuses both; a full run is separate.
  const Result again = cnclab("reproduce exps --quick --quiet");
  EXPECT_EQ(again.code, 0);
  EXPECT_EQ(again.out.find(" ran "), std::string::npos) << again.out;
  EXPECT_EQ(cnclab("reproduce exps --quick --profile other").code, 2);
}

TEST_F(Cli, ImpossibleDatasetIsAResourceErrorNotACrash) {
  const Result r = cnclab(quick("dataset.options.samples=100000000 dataset.options.inputs=10000"));
  expect_one_line_error(r, 1, "needs about");
  EXPECT_NE(r.err.find("TiB"), std::string::npos) << r.err;
  EXPECT_TRUE(outputs().empty());
}

TEST_F(Cli, VersionNamesLibraries) {
  const Result r = cnclab("version");
  EXPECT_EQ(r.code, 0);
  for (const char* lib : {"cnclab", "HDF5", "Eigen", "yaml-cpp"}) {
    EXPECT_NE(r.out.find(lib), std::string::npos) << lib << "\n" << r.out;
  }
}

const std::string kGroove = CNCLAB_SOURCE_DIR "/experiments/trochoid/groove_table2.yaml";

// The first line of `text` containing `key`, with runs of spaces collapsed.
std::string words_of_line(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  if (at == std::string::npos) return "";
  const auto begin = text.rfind('\n', at) + 1;
  std::istringstream line(text.substr(begin, text.find('\n', at) - begin));
  std::string word, out;
  while (line >> word) out += (out.empty() ? "" : " ") + word;
  return out;
}

TEST_F(Cli, GcodeTrochoidWritesACompleteProgramAtomically) {
  const Result r =
      cnclab("gcode trochoid " + kGroove + " trochoid.groove_length=40 report.compare_with=" +
             CNCLAB_SOURCE_DIR "/results/reference/trochoid_table3.csv -o g.nc");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  const std::string nc = slurp(dir_ / "g.nc");
  EXPECT_EQ(nc.rfind("%\nO1004", 0), 0u) << nc.substr(0, 80);
  EXPECT_NE(nc.find("G21 G17 G90 G94"), std::string::npos);
  EXPECT_NE(nc.find("G00 Z5.000 (safe retract)"), std::string::npos);
  EXPECT_NE(nc.find("M30\n%\n"), std::string::npos);
  EXPECT_NE(r.out.find("trochoid radius R = (W - D)/2 = 4 mm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("trochoidal loops:"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("entry: helical ramp at 3 deg"), std::string::npos) << r.out;
  EXPECT_EQ(outputs().size(), 1u);  // g.nc only: no temporaries left
  const Result outside =
      cnclab("gcode trochoid " + kGroove + " trochoid.groove_length=40 entry.mode=outside" +
             " report.compare_with=" CNCLAB_SOURCE_DIR "/results/reference/trochoid_table3.csv" +
             " -o g.nc");
  ASSERT_EQ(outside.code, 0) << outside.err;
  EXPECT_NE(outside.out.find("entry: from outside the stock at x -11.000"), std::string::npos)
      << outside.out;
  expect_one_line_error(cnclab("gcode trochoid " + kGroove + " entry.mode=plunge -o g.nc"), 2,
                        "entry.mode");
  const Result v = cnclab("validate " + kGroove + " trochoid.step=1.2");
  EXPECT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.out.find("step: 1.2"), std::string::npos) << v.out;
  EXPECT_NE(v.out.find("kind: gcode"), std::string::npos) << v.out;
}

TEST_F(Cli, DegenerateGrooveIsAUsageErrorAndWritesNothing) {
  expect_one_line_error(
      cnclab("gcode trochoid " + kGroove + " trochoid.cutter_diameter=30 -o g.nc"), 2,
      "trochoid.cutter_diameter = 30: must be smaller than groove_width 28");
  expect_one_line_error(cnclab("gcode trochoid " + kGroove + " trochoid.step=0 -o g.nc"), 2,
                        "trochoid.step = 0");
  expect_one_line_error(cnclab("gcode helix " + kGroove + " -o g.nc"), 2, "unknown tool path");
  EXPECT_TRUE(outputs().empty());
  // validate of an invalid job file says only what is wrong, never "valid".
  const Result v = cnclab("validate " + kGroove + " trochoid.step=0");
  EXPECT_EQ(v.code, 2);
  EXPECT_EQ(v.out, "");
  EXPECT_NE(v.err.find("trochoid.step = 0"), std::string::npos) << v.err;
}

// Five tiny axis networks on a 3^5 grid, then `tables ik` reads their results
// with the paper's reference numbers.
TEST_F(Cli, ReproduceIkAndGcodeThenTablesIk) {
  fs::create_directories(dir_ / "experiments/ik");
  fs::create_directories(dir_ / "experiments/trochoid");
  for (const char* axis : {"X", "Y", "Z", "A", "C"}) {
    const std::string lower(1, static_cast<char>(axis[0] - 'A' + 'a'));
    write("experiments/ik/ik_" + lower + ".yaml",
          "name: ik_" + lower +
              "\nseed: 4\n"
              "dataset: {generator: ik_samples, targets: [" +
              axis +
              "], options: {values_per_input: 3}}\n"
              "split: {train_count: 100, test_count: 100}\n"
              "normalisation: {inputs: minmax, targets: minmax, target_range: [0.1, 0.9]}\n"
              "model: {hidden: [6, 4], hidden_activation: sigmoid, output_activation: sigmoid}\n"
              "trainer: {type: sgdm, learning_rate: 0.3, momentum: 0.5, epochs: 3}\n"
              // A declared quick profile (--profile names one) that changes
              // nothing: the results made without it are those of --profile quick.
              "profiles: {quick: {trainer.epochs: 3}}\n");
  }
  write("experiments/trochoid/g.yaml", "include: " + kGroove +
                                           "\nname: g\ntrochoid: {groove_length: 40}\n"
                                           "report: {compare_with: " CNCLAB_SOURCE_DIR
                                           "/results/reference/trochoid_table3.csv}\n");
  const Result r = cnclab("reproduce experiments --quiet");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_TRUE(fs::exists(dir_ / "results/g/g.nc"));
  EXPECT_TRUE(fs::exists(dir_ / "results/g/g-points.tsv"));
  EXPECT_NE(r.out.find("Table 3 IS Eq. 6"), std::string::npos) << r.out;
  // The G-code job's standard result: `show` prints it with its outputs, and
  // `compare` of two configs shows the differing key and the metric deltas.
  const Result g2 = cnclab("run experiments/trochoid/g.yaml trochoid.step=1.2 --quiet");
  ASSERT_EQ(g2.code, 0) << g2.err;
  std::string g2_file = g2.out.substr(g2.out.rfind('\n', g2.out.size() - 2) + 1);
  g2_file.pop_back();  // the newline
  EXPECT_EQ(g2_file.rfind("results/g/g-", 0), 0u) << g2.out;
  const Result shown = cnclab("show " + g2_file);
  EXPECT_NE(shown.out.find("experiment   g (kind: gcode)"), std::string::npos) << shown.out;
  EXPECT_NE(shown.out.find("output       program: g.nc"), std::string::npos) << shown.out;
  const Result cmp = cnclab("compare results/g --format csv");
  ASSERT_EQ(cmp.code, 0) << cmp.err;
  EXPECT_NE(cmp.out.find("\nconfig,trochoid.step,"), std::string::npos) << cmp.out;
  EXPECT_NE(cmp.out.find("\nmetric,loops,"), std::string::npos) << cmp.out;
  // No reference folder in the working directory: build/cnclab reads the
  // paper's numbers from the source tree (core/share_paths.hpp).
  EXPECT_NE(r.out.find("Seed 004 Table 5"), std::string::npos) << r.out;

  const Result t = cnclab("tables ik --reference " CNCLAB_SOURCE_DIR "/results/reference");
  ASSERT_EQ(t.code, 0) << t.err << t.out;
  EXPECT_NE(t.out.find("Seed 004 Table 5"), std::string::npos) << t.out;
  EXPECT_EQ(words_of_line(t.out, "Training set"),
            "Dataset Training set 100 1042 100 1042 100 1042 100 100");
  EXPECT_EQ(words_of_line(t.out, "Validation set"), "Validation set 43 348 43 348 43 348 43 43");
  EXPECT_NE(t.out.find("adds up to 2432"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("Machine-space error"), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("(n = 100,"), std::string::npos) << t.out;
  // csv and json carry numbers only: every column a number column (float or
  // empty) or a declared label column, read by Python's csv and json modules.
  for (const char* format : {"csv", "json"}) {
    const Result m =
        cnclab("tables ik --reference " CNCLAB_SOURCE_DIR "/results/reference --format " +
               std::string(format));
    ASSERT_EQ(m.code, 0) << m.err << m.out;
    write(std::string("ik.") + format, m.out);
  }
  const Result machine =
      sh("/usr/bin/python3 " CNCLAB_SOURCE_DIR "/tests/report/machine_tables.py ik.csv ik.json");
  EXPECT_EQ(machine.code, 0) << machine.out << machine.err;
  // Each table names the files it read: the paper's numbers and the results.
  const std::string sources = "\nsources: " CNCLAB_SOURCE_DIR
                              "/results/reference/ik_table5.yaml, "
                              "results/ik_x/ik_x-seed4-";
  EXPECT_NE(t.out.find(sources), std::string::npos) << t.out;
  EXPECT_NE(t.out.find("\nsources: results/ik_x/ik_x-seed4-"), std::string::npos) << t.out;

  // No search or trainbr results: said in the notes, the rest printed. The
  // project has no such experiment files: the source tree's are used.
  EXPECT_NE(t.out.find("- search: no results for any axis; X not available: no result for " +
                       fs::path(CNCLAB_SOURCE_DIR "/experiments/ik_search/search_x.yaml").string()),
            std::string::npos)
      << t.out;
  EXPECT_NE(t.out.find("- trainbr: no results for any axis; X not available: no result for " +
                       fs::path(CNCLAB_SOURCE_DIR "/experiments/ik_trainbr/ik_x.yaml").string()),
            std::string::npos)
      << t.out;
  EXPECT_EQ(t.out.find("X trainbr"), std::string::npos) << t.out;

  // A trainbr network for X only: its columns beside ours (other axes n/a),
  // and its machine-space row with the other four networks taken from ours.
  fs::create_directories(dir_ / "experiments/ik_trainbr");
  write("experiments/ik_trainbr/ik_x.yaml",
        "name: ik_trainbr_x\nseed: 4\n"
        "dataset: {generator: ik_samples, targets: [X], options: {values_per_input: 3}}\n"
        "split: {train_count: 100, test_count: 100}\n"
        "normalisation: {inputs: minmax, targets: minmax, target_range: [0.1, 0.9]}\n"
        "model: {hidden: [6, 4], hidden_activation: sigmoid, output_activation: sigmoid}\n"
        "trainer: {type: trainbr, epochs: 3}\n");
  ASSERT_EQ(cnclab("reproduce experiments/ik_trainbr --quiet").code, 0);
  const Result b = cnclab("tables ik --reference " CNCLAB_SOURCE_DIR "/results/reference");
  ASSERT_EQ(b.code, 0) << b.err << b.out;
  EXPECT_EQ(words_of_line(b.out, "Training set"),
            "Dataset Training set 100 100 1042 100 n/a 1042 100 n/a 1042");
  EXPECT_EQ(words_of_line(b.out, "LR"), "Learning rate LR 0.3 - 0.11 0.3 n/a 0.71 0.3 n/a 0.71");
  EXPECT_NE(b.out.find("- trainbr *: Y, Z, A, C from ours (no trainbr result)"), std::string::npos)
      << b.out;
  EXPECT_EQ(b.out.find("- trainbr: X not available"), std::string::npos) << b.out;
  EXPECT_NE(b.out.find("- trainbr: C not available: no result for " +
                       fs::path(CNCLAB_SOURCE_DIR "/experiments/ik_trainbr/ik_c.yaml").string()),
            std::string::npos)
      << b.out;

  // A search for X (kind: sweep) through reproduce: ran, then reused; the
  // table shows the selected trial's sizes beside ours.
  fs::create_directories(dir_ / "experiments/ik_search");
  write("experiments/ik_search/search_x.yaml",
        "kind: sweep\nname: ik_search_x\nexperiment: ../ik/ik_x.yaml\njobs: 2\n"
        "sweep:\n  objective: {metric: normalised_validation_mse}\n"
        "  parameters: {model.hidden: [[3, 2], [5, 3]]}\n");
  const Result s1 = cnclab("reproduce experiments/ik_search --quiet");
  ASSERT_EQ(s1.code, 2) << s1.err << s1.out;  // ik_x lacks normalised_validation_mse
  EXPECT_NE(s1.out.find("is not among the experiment's metrics"), std::string::npos) << s1.out;
  write("experiments/ik_search/search_x.yaml",
        "kind: sweep\nname: ik_search_x\nexperiment: ../ik/ik_x.yaml\njobs: 2\n"
        "overrides: ['metrics=[mse, normalised_validation_mse]']\n"
        "sweep:\n  objective: {metric: normalised_validation_mse}\n"
        "  parameters: {model.hidden: [[3, 2], [5, 3]]}\n");
  const Result s2 = cnclab("reproduce experiments/ik_search --quiet");
  ASSERT_EQ(s2.code, 0) << s2.err << s2.out;
  EXPECT_NE(s2.out.find("ik_search_x                  ran          2 trial(s) had no result"),
            std::string::npos)
      << s2.out;
  const Result s3 = cnclab("reproduce experiments/ik_search --quiet");
  ASSERT_EQ(s3.code, 0) << s3.err << s3.out;
  EXPECT_NE(s3.out.find("ik_search_x                  reused       sweep plan unchanged"),
            std::string::npos)
      << s3.out;
  const Result c = cnclab("tables ik --reference " CNCLAB_SOURCE_DIR "/results/reference");
  ASSERT_EQ(c.code, 0) << c.err << c.out;
  const std::string hidden1 = words_of_line(c.out, "Hidden layer1");
  EXPECT_TRUE(hidden1.rfind("Hidden layer1 6 3 6 25 6 n/a n/a 22", 0) == 0 ||
              hidden1.rfind("Hidden layer1 6 5 6 25 6 n/a n/a 22", 0) == 0)
      << c.out;
  EXPECT_NE(c.out.find("- search: X: the best point by mean validation.normalised_mse of 2 (2 "
                       "complete trial(s) of 2 planned), its median repeat"),
            std::string::npos)
      << c.out;

  // One rule for results folders: `--results ROOT --profile
  // P` reads ROOT/P, as `reproduce --out ROOT --profile P` writes; a folder
  // in the layout that wrote ROOT itself still works, with a note.
  const std::string tables_quick =
      "tables ik --reference " CNCLAB_SOURCE_DIR "/results/reference --profile quick --results ";
  fs::create_directories(dir_ / "root");
  fs::rename(dir_ / "results", dir_ / "root/quick");
  const Result rooted = cnclab(tables_quick + "root");
  ASSERT_EQ(rooted.code, 0) << rooted.err << rooted.out;
  EXPECT_EQ(words_of_line(rooted.out, "Hidden layer1"), hidden1) << rooted.out;
  EXPECT_EQ(rooted.err, "");
  fs::rename(dir_ / "root/quick", dir_ / "legacy");  // results directly in ROOT
  const Result legacy = cnclab(tables_quick + "legacy");
  ASSERT_EQ(legacy.code, 0) << legacy.err << legacy.out;
  EXPECT_EQ(words_of_line(legacy.out, "Hidden layer1"), hidden1) << legacy.out;
  EXPECT_NE(legacy.err.find("note: legacy holds results directly and has no quick/ folder"),
            std::string::npos)
      << legacy.err;
  const Result reused = cnclab("reproduce experiments/ik --quiet --profile quick --out legacy");
  ASSERT_EQ(reused.code, 0) << reused.err << reused.out;
  // Found in place: no experiment's status column says ran (the tables'
  // notes say what the runs "ran with").
  EXPECT_EQ(reused.out.find("  ran  "), std::string::npos) << reused.out;
  EXPECT_FALSE(fs::exists(dir_ / "legacy/quick"));
  fs::rename(dir_ / "legacy", dir_ / "results");

  expect_one_line_error(cnclab("tables nosuch"), 2, "unknown table 'nosuch'; known: ik");
  const Result list = cnclab("tables");
  EXPECT_EQ(list.code, 0);
  EXPECT_EQ(list.out.rfind("ik  seed 004 Table 5", 0), 0u) << list.out;
  fs::remove_all(dir_ / "results/ik_c");
  expect_one_line_error(cnclab("tables ik --reference " CNCLAB_SOURCE_DIR "/results/reference"), 1,
                        "no result for experiments/ik/ik_c.yaml");
}

}  // namespace
