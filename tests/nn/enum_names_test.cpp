// Every value of the nn enums has a name that parses back to it (the tables
// in activation.cpp, scaling.cpp and narx_predictor.cpp list them all).
#include <gtest/gtest.h>

#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/activation.hpp"
#include "cnclab/nn/narx_predictor.hpp"
#include "cnclab/nn/scaling.hpp"

namespace cnclab {
namespace {

TEST(NnEnumNames, EveryValueRoundTrips) {
  for (int i = 0; i <= static_cast<int>(Activation::linear); ++i) {
    const auto a = static_cast<Activation>(i);
    EXPECT_NE(to_string(a), "?") << i;
    EXPECT_EQ(parse_activation(to_string(a)), a) << i;
  }
  EXPECT_THROW(parse_activation("softmax"), OptionError);
  for (int i = 0; i <= static_cast<int>(Scaling::none); ++i) {
    const auto s = static_cast<Scaling>(i);
    Scaling parsed{};
    ASSERT_TRUE(parse_scaling(to_string(s), parsed)) << i;
    EXPECT_EQ(parsed, s);
  }
  Scaling untouched = Scaling::minmax;
  EXPECT_FALSE(parse_scaling("robust", untouched));
  EXPECT_EQ(untouched, Scaling::minmax);
  for (int i = 0; i <= static_cast<int>(PredictorStatus::undefined_tangent); ++i) {
    EXPECT_STRNE(to_string(static_cast<PredictorStatus>(i)), "?") << i;
  }
}

}  // namespace
}  // namespace cnclab
