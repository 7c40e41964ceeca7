// `cnclab init DIR` from the build tree (its template: the source tree's
// templates/project, core/share_paths.hpp): the files it makes, exit 2 on a
// non-empty folder, --force keeping what is there, and the starters valid
// with their includes found. The installed case: install_test.py.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace {
namespace fs = std::filesystem;

const std::string kInitCnclab = CNCLAB_BINARY_DIR "/cnclab";

// The template's files, each of which a new project has.
const char* const kInitProjectFiles[] = {
    "README.md",
    ".gitignore",
    "configs/README.md",
    "experiments/step_error/surface1.yaml",
    "experiments/contour_error/narx.yaml",
    "experiments/five_axis/ik_x.yaml",
    "experiments/five_axis/trochoid_groove.yaml",
};

TEST(CliInit, MakesAProjectWhoseStartersValidate) {
  cnclab::testing::TempDir dir;
  const auto r = cnclab::testing::run_shell(dir.path(), kInitCnclab + " init deep/proj");
  ASSERT_EQ(r.code, 0) << r.err;
  const fs::path proj = dir / "deep/proj";
  for (const char* file : kInitProjectFiles) {
    EXPECT_TRUE(fs::is_regular_file(proj / file)) << file;
    EXPECT_NE(r.out.find(std::string("  ") + file + "\n"), std::string::npos) << file << r.out;
    // A copy of the template file.
    EXPECT_EQ(cnclab::testing::slurp(proj / file),
              cnclab::testing::slurp(fs::path(CNCLAB_SOURCE_DIR "/templates/project") / file))
        << file;
  }
  EXPECT_TRUE(fs::is_directory(proj / "datasets"));
  EXPECT_TRUE(fs::is_directory(proj / "results"));
  for (const char* file : kInitProjectFiles) {
    if (fs::path(file).extension() != ".yaml") continue;
    const auto v = cnclab::testing::run_shell(proj, kInitCnclab + " validate " + file);
    EXPECT_EQ(v.code, 0) << file << v.err;
  }
}

TEST(CliInit, RefusesANonEmptyFolderUnlessForcedAndThenKeepsEveryFile) {
  cnclab::testing::TempDir dir;
  fs::create_directories(dir / "proj");
  std::ofstream(dir / "proj/README.md") << "mine\n";
  const auto refused = cnclab::testing::run_shell(dir.path(), kInitCnclab + " init proj");
  EXPECT_EQ(refused.code, 2);
  EXPECT_NE(refused.err.find("cnclab: error: init: proj is not empty (README.md); "),
            std::string::npos)
      << refused.err;
  EXPECT_NE(refused.err.find("--force"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "proj/experiments"));

  const auto forced = cnclab::testing::run_shell(dir.path(), kInitCnclab + " init proj --force");
  ASSERT_EQ(forced.code, 0) << forced.err;
  EXPECT_EQ(cnclab::testing::slurp(dir / "proj/README.md"), "mine\n");
  EXPECT_NE(forced.out.find("README.md (exists: kept)"), std::string::npos) << forced.out;
  EXPECT_TRUE(fs::is_regular_file(dir / "proj/experiments/five_axis/ik_x.yaml"));

  std::ofstream(dir / "file") << "x";
  const auto file = cnclab::testing::run_shell(dir.path(), kInitCnclab + " init file --force");
  EXPECT_EQ(file.code, 2);
  EXPECT_NE(file.err.find("init: file exists and is not a folder"), std::string::npos) << file.err;
}

}  // namespace
