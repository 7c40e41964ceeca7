// `cnclab init`'s project (pipeline/project_init.hpp) against the template
// folder itself: every template file copied byte for byte, an existing file
// kept with force, and the refusals.
#include "cnclab/pipeline/project_init.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/share_paths.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

std::string contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(ProjectInit, CopiesEveryTemplateFileAndMakesTheEmptyFolders) {
  const fs::path source = require_installed("templates/project");
  testing::TempDir dir;
  std::ostringstream out;
  EXPECT_EQ(init_command({dir / "deep/proj", false}, out), 0);
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(source)) {
    if (!e.is_regular_file()) continue;
    ++files;
    const fs::path copy = dir / "deep/proj" / e.path().lexically_relative(source);
    EXPECT_EQ(contents(copy), contents(e.path())) << copy;
  }
  ASSERT_GT(files, 0u);
  EXPECT_TRUE(fs::is_directory(dir / "deep/proj/datasets"));
  EXPECT_TRUE(fs::is_directory(dir / "deep/proj/results"));
  EXPECT_NE(out.str().find(": " + std::to_string(files) + " file(s) from "), std::string::npos)
      << out.str();
}

TEST(ProjectInit, RefusesAFileAndANonEmptyFolderAndKeepsFilesWithForce) {
  testing::TempDir dir;
  std::ofstream(dir / "file") << "x";
  std::ostringstream out;
  EXPECT_THROW(init_command({dir / "file", true}, out), ConfigError);
  fs::create_directories(dir / "proj");
  std::ofstream(dir / "proj/README.md") << "mine\n";
  EXPECT_THROW(init_command({dir / "proj", false}, out), ConfigError);
  EXPECT_EQ(init_command({dir / "proj", true}, out), 0);
  EXPECT_EQ(contents(dir / "proj/README.md"), "mine\n");
  EXPECT_NE(out.str().find("  README.md (exists: kept)\n"), std::string::npos) << out.str();
}

}  // namespace
}  // namespace cnclab
