#include "cnclab/core/enum_names.hpp"

#include <gtest/gtest.h>

#include <string>

namespace cnclab {
namespace {

enum class Colour { red, green, blue };
constexpr EnumName<Colour> kColourNames[] = {{Colour::red, "red"}, {Colour::green, "green"}};

TEST(EnumNames, NamesValuesAndTheUnlistedValue) {
  EXPECT_STREQ(enum_name(kColourNames, Colour::green), "green");
  EXPECT_STREQ(enum_name(kColourNames, Colour::blue), "?");  // not in the table
  EXPECT_STREQ(enum_name(kColourNames, Colour::blue, "unknown"), "unknown");
  EXPECT_EQ(enum_value(kColourNames, "red"), Colour::red);
  EXPECT_FALSE(enum_value(kColourNames, "Red"));  // exact, case-sensitive
  EXPECT_FALSE(enum_value(kColourNames, ""));
  EXPECT_EQ(enum_name_list(kColourNames), "red, green");
  static_assert(enum_value(kColourNames, "green") == Colour::green);
}

}  // namespace
}  // namespace cnclab
