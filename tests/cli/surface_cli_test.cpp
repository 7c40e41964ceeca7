// `cnclab surface` and CAD surfaces in `cnclab dataset generate`, end to end:
// exit codes, one-line errors and nothing written on bad files or faces
// that cannot be machined. Skipped where the build has no OCCT (`cnclab surface show` then
// fails with the package to install, checked here too).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "common/process.hpp"

namespace {
namespace fs = std::filesystem;

const std::string kCnclab = CNCLAB_BINARY_DIR "/cnclab";
const std::string kSurface1 = CNCLAB_SOURCE_DIR "/configs/surfaces/surface1.yaml";

class SurfaceCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("cnclab_surface_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + "_" +
            std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    occt_ = cnclab("surface show " + kSurface1).err.find("libocct") == std::string::npos;
  }
  void TearDown() override { fs::remove_all(dir_); }

  cnclab::testing::ShellResult cnclab(const std::string& args) const {
    return cnclab::testing::run_shell(dir_, kCnclab + " " + args);
  }
  void write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
  }
  std::size_t file_count() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir_), {}));
  }
  // A dataset config naming a face of `file`.
  void write_config(const std::string& file, int face) const {
    write("d.yaml", "dataset:\n  generator: step_error\n  options:\n    surface: {file: " + file +
                        ", face: " + std::to_string(face) +
                        "}\n    lines: 3\n    points_per_line: 5\n    curve_points: 2\n");
  }

  fs::path dir_;
  bool occt_ = true;
};

void expect_one_line_error(const cnclab::testing::ShellResult& r, const std::string& fragment) {
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
}

TEST_F(SurfaceCli, ExportShowAndGenerate) {
  if (!occt_) GTEST_SKIP() << "built without Open CASCADE";
  auto r = cnclab("surface export " + kSurface1 + " --out s1.step");
  ASSERT_EQ(r.code, 0) << r.err;
  r = cnclab("surface show s1.step");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("1 face"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("bspline"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("3 x 3"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("(120, 140, 38)"), std::string::npos) << r.out;  // surface1's box
  r = cnclab("surface example-part --freeform " + kSurface1 + " --out part.stp");
  ASSERT_EQ(r.code, 0) << r.err;
  r = cnclab("surface show part.stp");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* type : {"bspline", "cylinder", "plane", "sphere"}) {
    EXPECT_NE(r.out.find(type), std::string::npos) << r.out;
  }
  for (const char* part :
       {"4 faces; unit millimetre; written by Open CASCADE 7.6", "trimmed", "holes", "n·axis",
        "min radius [mm]", "usable", "40 convex", "60 convex"}) {
    EXPECT_NE(r.out.find(part), std::string::npos) << part << "\n" << r.out;
  }
  write_config("part.stp", 2);
  r = cnclab("dataset generate d.yaml --out d.h5 -q");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "d.h5"));
  // A face of a CAD file exported alone reads back as one face of its type's NURBS form.
  r = cnclab("surface export part.stp --face 4 --out cap.igs");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("face 4 of part.stp: a sphere as a NURBS face"), std::string::npos) << r.err;
  r = cnclab("surface show cap.igs");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("1 face; unit mm"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("60 convex"), std::string::npos) << r.out;  // the sphere's radius
}

// Where a face cannot be machined as the options say, `dataset generate`
// exits 2 with one line naming the file, the face, the line and the reason,
// and writes nothing; the read time limit names its option.
TEST_F(SurfaceCli, RefusedFacesNameFileFaceAndLine) {
  if (!occt_) GTEST_SKIP() << "built without Open CASCADE";
  const std::string sphere = CNCLAB_SOURCE_DIR "/tests/cad/data/revolved_sphere.step";
  write_config(sphere, 1);
  expect_one_line_error(cnclab("dataset generate d.yaml --out d.h5 -q"),
                        "face 1 of " + sphere + ": line 0 (v = -1.5708), CC point 0");
  auto r = cnclab(
      "dataset generate d.yaml --out d.h5 -q dataset.options.unreachable=clip "
      "dataset.options.lines=20 dataset.options.points_per_line=20");
  EXPECT_EQ(r.code, 0) << r.err;
  write("t.yaml", "dataset:\n  generator: step_error\n  options:\n    surface: {file: " + sphere +
                      ", face: 1, read_timeout: 0.001}\n");
  expect_one_line_error(cnclab("dataset generate t.yaml --out t.h5 -q"),
                        "timed out after 0.001 s reading it");
  expect_one_line_error(cnclab("surface show " + sphere + " --read-timeout 0.001"),
                        "read_timeout (seconds) in the dataset's surface");
  expect_one_line_error(cnclab("surface export " + sphere + " --out x.step"), "--face N");
  EXPECT_FALSE(fs::exists(dir_ / "t.h5"));
  EXPECT_FALSE(fs::exists(dir_ / "x.step"));
  r = cnclab("surface show " + sphere + " --why");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("no: degenerate"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("S_u x S_v vanishes there"), std::string::npos) << r.out;
}

TEST_F(SurfaceCli, BadFilesAreUsageErrorsAndWriteNothing) {
  if (!occt_) {
    expect_one_line_error(cnclab("surface show x.step"), "libocct-data-exchange-dev");
    return;
  }
  ASSERT_EQ(cnclab("surface export " + kSurface1 + " --out good.step").code, 0);
  std::ifstream in(dir_ / "good.step");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  write("truncated.step", text.substr(0, text.size() / 3));
  write("notcad.step", "degree_u: 3\n");
  write("notcad.igs", "hello\n");
  write("empty.step", "");
  const std::size_t before = file_count();
  expect_one_line_error(cnclab("surface show notcad.step"), "notcad.step: not a readable STEP");
  expect_one_line_error(cnclab("surface show notcad.igs"), "notcad.igs: ");
  expect_one_line_error(cnclab("surface show truncated.step"), "truncated.step: ");
  expect_one_line_error(cnclab("surface show empty.step"), "empty.step: ");
  expect_one_line_error(cnclab("surface show missing.step"), "missing.step: no such file");
  expect_one_line_error(cnclab("surface export " + kSurface1 + " --out x.txt"),
                        "not a CAD file name");
  for (const auto& [file, face, fragment] :
       {std::tuple{"truncated.step", 1, "truncated.step: "},
        std::tuple{"notcad.step", 1, "not a readable STEP file"},
        std::tuple{"good.step", 2, "face 2 does not exist; the file has 1 face"},
        std::tuple{"good.step", 0, "must be a face number >= 1"}}) {
    write_config(file, face);
    expect_one_line_error(cnclab("dataset generate d.yaml --out d.h5 -q"), fragment);
  }
  EXPECT_EQ(file_count(), before + 1);  // d.yaml only
  EXPECT_FALSE(fs::exists(dir_ / "d.h5"));
  EXPECT_FALSE(fs::exists(dir_ / "x.txt"));
}

}  // namespace
