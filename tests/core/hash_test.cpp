#include "cnclab/core/hash.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace cnclab
