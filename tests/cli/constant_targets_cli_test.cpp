// Near-constant targets (data/constant_targets.hpp) are said where the
// dataset is made, not only on the result: `dataset generate` warns, and a
// `run` that generates its dataset warns on the log before training and puts
// "constant targets" on the result. The plane's step errors are rounding
// noise (a chord between two points of a straight path on a plane lies on
// the plane: the step error is zero); surface 1's are not.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace {
namespace fs = std::filesystem;

const std::string kConstantTargetsCnclab = CNCLAB_BINARY_DIR "/cnclab";
const std::string kTunedSurface1 = CNCLAB_SOURCE_DIR "/experiments/step_error/tuned/surface1.yaml";
// z = 10 + 0.18 (x - 260): an inclined plane, like the CAD example's plane face.
const std::string kPlane =
    "{degree_u: 1, degree_v: 1, knots_u: [0, 0, 1, 1], knots_v: [0, 0, 1, 1], control_points: "
    "[[[260, 0, 10], [260, 50, 10]], [[298, 0, 16.84], [298, 50, 16.84]]]}";
const std::string kNoSpread = "target step_error has no spread to learn";

class ConstantTargetsCli : public ::testing::Test {
 protected:
  cnclab::testing::ShellResult cnclab(const std::string& args) const {
    return cnclab::testing::run_shell(dir_.path(), kConstantTargetsCnclab + " " + args);
  }
  // A small step-error experiment (6 lines x 8 points, 1 epoch) on `surface`.
  void write_experiment(const std::string& name, const std::string& surface) const {
    std::ofstream(dir_ / (name + ".yaml"))
        << "include: " << kTunedSurface1 << "\nname: " << name
        << "\ndataset:\n  options:\n    surface: " << surface
        << "\n    lines: 6\n    points_per_line: 8\ntrainer: {epochs: 1}\n";
  }
  cnclab::testing::TempDir dir_;
};

TEST_F(ConstantTargetsCli, DatasetGenerationAndRunWarnOnAPlaneNotOnSurface1) {
  write_experiment("plane", kPlane);
  write_experiment("curved", "\"" CNCLAB_SOURCE_DIR "/configs/surfaces/surface1.yaml\"");

  const auto generated = cnclab("dataset generate plane.yaml --out plane.h5 --quiet");
  EXPECT_EQ(generated.code, 0) << generated.err;
  EXPECT_NE(generated.err.find("warning: " + kNoSpread), std::string::npos) << generated.err;
  EXPECT_NE(generated.err.find("below the generator's resolution 1e-06 µm"), std::string::npos)
      << generated.err;
  EXPECT_TRUE(fs::exists(dir_ / "plane.h5"));  // a warning, not an error
  const auto curved = cnclab("dataset generate curved.yaml --out curved.h5 --quiet");
  EXPECT_EQ(curved.code, 0) << curved.err;
  EXPECT_EQ(curved.err.find(kNoSpread), std::string::npos) << curved.err;

  // A run generating its dataset: the cache's warning, then the result's.
  const auto ran = cnclab("run plane.yaml --out r --data-dir d");
  EXPECT_EQ(ran.code, 0) << ran.err;
  const auto at_generation = ran.err.find(kNoSpread);
  const auto on_result = ran.err.find("warning: plane: constant targets (step_error)");
  EXPECT_NE(at_generation, std::string::npos) << ran.err;
  EXPECT_NE(on_result, std::string::npos) << ran.err;
  EXPECT_LT(at_generation, on_result) << ran.err;
  const auto again = cnclab("run curved.yaml --out r --data-dir d");
  EXPECT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(again.err.find("constant targets"), std::string::npos) << again.err;
  EXPECT_EQ(again.err.find(kNoSpread), std::string::npos) << again.err;
}

}  // namespace
