#include "cnclab/core/hash.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

// Published FNV-1a 64-bit test vectors (Fowler/Noll/Vo reference test suite).
TEST(Hash, MatchesPublishedFnv1aVectors) {
  EXPECT_EQ(hash_hex(""), "cbf29ce484222325");
  EXPECT_EQ(hash_hex("a"), "af63dc4c8601ec8c");
  EXPECT_EQ(hash_hex("foobar"), "85944171f73967e8");
}

TEST(Hash, IncrementalEqualsWhole) {
  EXPECT_EQ(Hasher().add("foo").add("bar").hex(), hash_hex("foobar"));
}

// A file of several read chunks (1 MiB each) hashes as its bytes do; an
// unreadable file has no hash.
TEST(Hash, FileHashIsTheHashOfItsBytes) {
  testing::TempDir dir;
  std::string bytes;
  for (std::size_t i = 0; i < 2'500'000; ++i) bytes.push_back(static_cast<char>((i * 7919) % 251));
  std::ofstream(dir / "f.bin", std::ios::binary) << bytes;
  EXPECT_EQ(file_hash_hex(dir / "f.bin"), hash_hex(bytes));
  std::ofstream(dir / "empty.bin", std::ios::binary);
  EXPECT_EQ(file_hash_hex(dir / "empty.bin"), "cbf29ce484222325");
  EXPECT_EQ(file_hash_hex(dir / "missing.bin"), std::nullopt);
}

}  // namespace
}  // namespace cnclab
