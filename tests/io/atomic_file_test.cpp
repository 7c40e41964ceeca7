#include "cnclab/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> names_in(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(AtomicOutput, OnlyThePartialNameExistsBeforeCommitAndOnlyTheFinalAfter) {
  TempDir dir;
  const auto final_path = dir / "sub/r.h5";
  AtomicOutput out(final_path);
  EXPECT_TRUE(fs::is_directory(dir / "sub"));  // parent created
  EXPECT_EQ(out.temp_path().parent_path(), final_path.parent_path());
  std::ofstream(out.temp_path()) << "data";
  EXPECT_EQ(names_in(dir / "sub"), (std::vector<std::string>{out.temp_path().filename()}));
  EXPECT_TRUE(is_partial_path(out.temp_path()));
  EXPECT_FALSE(is_partial_path(final_path));
  out.commit();
  EXPECT_EQ(names_in(dir / "sub"), (std::vector<std::string>{"r.h5"}));
  EXPECT_EQ(slurp(final_path), "data");
}

TEST(AtomicOutput, TemporaryNameFollowsTheDocumentedPattern) {
  TempDir dir;
  AtomicOutput out(dir / "r.h5");
  const std::string name = out.temp_path().filename().string();
  const std::string prefix = ".r.h5.partial-" + std::to_string(::getpid()) + "-";
  ASSERT_EQ(name.substr(0, prefix.size()), prefix);
  EXPECT_EQ(name.size(), prefix.size() + 16);
}

TEST(AtomicOutput, CommitReplacesAnExistingFile) {
  TempDir dir;
  const auto final_path = dir / "r.h5";
  std::ofstream(final_path) << "old";
  AtomicOutput out(final_path);
  std::ofstream(out.temp_path()) << "new";
  out.commit();
  EXPECT_EQ(slurp(final_path), "new");
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"r.h5"}));
}

TEST(AtomicOutput, AbandonedWriteLeavesPreviousFileIntactAndNoTemporary) {
  TempDir dir;
  const auto final_path = dir / "r.h5";
  std::ofstream(final_path) << "old";
  fs::path temp;
  {
    AtomicOutput out(final_path);
    temp = out.temp_path();
    std::ofstream(temp) << "new but unfinished";
  }
  EXPECT_FALSE(fs::exists(temp));
  EXPECT_EQ(slurp(final_path), "old");
  EXPECT_EQ(names_in(dir.path()), (std::vector<std::string>{"r.h5"}));
}

TEST(AtomicOutput, DestructorWithoutCommitRemovesTheTemporary) {
  TempDir dir;
  fs::path temp;
  {
    AtomicOutput out(dir / "new.h5");
    temp = out.temp_path();
    std::ofstream(temp) << "x";
    ASSERT_TRUE(fs::exists(temp));
  }
  EXPECT_TRUE(fs::is_empty(dir.path()));
}

TEST(AtomicOutput, CommitWithoutAWrittenTemporaryFailsAndKeepsTheOldFile) {
  TempDir dir;
  const auto final_path = dir / "r.h5";
  std::ofstream(final_path) << "old";
  AtomicOutput out(final_path);
  try {
    out.commit();
    FAIL() << "expected IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(final_path.string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(final_path), "old");
}

TEST(AtomicOutput, TwoWritersGetDistinctTemporaries) {
  TempDir dir;
  AtomicOutput a(dir / "r.h5"), b(dir / "r.h5");
  EXPECT_NE(a.temp_path(), b.temp_path());
}

TEST(AtomicOutput, IsPartialPathMatchesOnlyThePattern) {
  EXPECT_TRUE(is_partial_path("results/.x.h5.partial-123-0123456789abcdef"));
  EXPECT_TRUE(is_partial_path(".a.partial-b.partial-1-0123456789abcdef"));
  EXPECT_FALSE(is_partial_path("results/x.h5"));
  EXPECT_FALSE(is_partial_path("results/.x.h5"));
  EXPECT_FALSE(is_partial_path("x.h5.partial-123-0123456789abcdef"));   // no leading dot
  EXPECT_FALSE(is_partial_path(".partial-123-0123456789abcdef"));       // no name
  EXPECT_FALSE(is_partial_path(".x.h5.partial-notes"));                 // no pid-tag
  EXPECT_FALSE(is_partial_path(".x.h5.partial-123-0123456789abcde"));   // 15 hex digits
  EXPECT_FALSE(is_partial_path(".x.h5.partial-12a-0123456789abcdef"));  // pid not decimal
  EXPECT_FALSE(is_partial_path(".x.h5.partial-123-0123456789ABCDEF"));  // upper-case hex
}

}  // namespace
}  // namespace cnclab
