#include "cnclab/io/atomic_file.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

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

TEST(AtomicOutput, OnlyThePartialNameExistsBeforeCommit) {
  TempDir dir;
  const auto final_path = dir / "sub/r.h5";
  AtomicOutput out(final_path);
  std::ofstream(out.temp_path()) << "data";
  EXPECT_TRUE(fs::exists(out.temp_path()));
  EXPECT_FALSE(fs::exists(final_path));
  EXPECT_TRUE(is_partial_path(out.temp_path()));
  EXPECT_FALSE(is_partial_path(final_path));
  EXPECT_EQ(out.temp_path().parent_path(), final_path.parent_path());
  out.commit();
  EXPECT_FALSE(fs::exists(out.temp_path()));
  EXPECT_EQ(slurp(final_path), "data");
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
}

TEST(AtomicOutput, TwoWritersGetDistinctTemporaries) {
  TempDir dir;
  AtomicOutput a(dir / "r.h5"), b(dir / "r.h5");
  EXPECT_NE(a.temp_path(), b.temp_path());
}

}  // namespace
}  // namespace cnclab
