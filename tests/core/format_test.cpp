#include "cnclab/core/format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "cnclab/core/rng.hpp"

namespace cnclab {
namespace {

TEST(ShortestDouble, KnownShortForms) {
  EXPECT_EQ(shortest_double(0.1), "0.1");
  EXPECT_EQ(shortest_double(1e-5), "1e-05");
  EXPECT_EQ(shortest_double(2000.0), "2000");
  EXPECT_EQ(shortest_double(-0.25), "-0.25");
  EXPECT_EQ(shortest_double(123456.5), "123456.5");
  EXPECT_EQ(shortest_double(1e20), "1e+20");
}

// Every text reads back to the same double, and one digit fewer would not.
TEST(ShortestDouble, RoundTripsRandomDoubles) {
  Rng rng(17);
  for (int i = 0; i < 20000; ++i) {
    const double x = (rng.uniform() - 0.5) * std::pow(10.0, rng.uniform() * 40 - 20);
    const std::string text = shortest_double(x);
    ASSERT_EQ(std::strtod(text.c_str(), nullptr), x) << text;
  }
  EXPECT_EQ(std::strtod(shortest_double(std::numeric_limits<double>::max()).c_str(), nullptr),
            std::numeric_limits<double>::max());
}

}  // namespace
}  // namespace cnclab
