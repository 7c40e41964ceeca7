// Edit distance against hand-counted cases, and the near-miss rule.
#include "cnclab/core/suggest.hpp"

#include <gtest/gtest.h>

namespace cnclab {
namespace {

TEST(Suggest, EditDistanceCountsEachEditOnce) {
  EXPECT_EQ(edit_distance("", ""), 0u);
  EXPECT_EQ(edit_distance("abc", ""), 3u);
  EXPECT_EQ(edit_distance("kitten", "sitting"), 3u);  // k->s, e->i, +g
  EXPECT_EQ(edit_distance("rsme", "rmse"), 1u);       // one transposition
  EXPECT_EQ(edit_distance("momentm", "momentum"), 1u);
  EXPECT_EQ(edit_distance("adam", "sgdm"), 3u);
}

TEST(Suggest, OnlyNearMissesAreSuggested) {
  const std::vector<std::string> metrics = {"mse", "rmse", "mae"};
  EXPECT_EQ(did_you_mean("rsme", metrics), " (did you mean 'rmse'?)");
  EXPECT_EQ(did_you_mean("accuracy", metrics), "");
  EXPECT_EQ(closest_name("ms", metrics), "mse");  // the first of equals (mse, mae: 1 each)
}

}  // namespace
}  // namespace cnclab
