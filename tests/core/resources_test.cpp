#include "cnclab/core/resources.hpp"

#include <gtest/gtest.h>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

TEST(Resources, FormatBytes) {
  EXPECT_EQ(format_bytes(512), "512 B");
  EXPECT_EQ(format_bytes(1536), "1.5 KiB");
  EXPECT_EQ(format_bytes(8e12), "7.3 TiB");
}

TEST(Resources, ImpossibleSizeIsAResourceErrorNamingIt) {
  try {
    check_memory(8e18, "the dataset");
    FAIL();
  } catch (const ResourceError& e) {
    EXPECT_NE(std::string(e.what()).find("the dataset needs about 6.9 EiB"), std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(check_memory(1024, "a tiny thing"));
  EXPECT_GT(memory_budget_bytes(), 1u << 20);
}

}  // namespace
}  // namespace cnclab
