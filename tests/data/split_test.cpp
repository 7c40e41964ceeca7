#include "cnclab/data/split.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

TEST(Split, DisjointCoveringSortedWithRoundedSizes) {
  Rng rng(5);
  const Split s = make_random_split(101, {0.7, 0.1}, rng);
  EXPECT_EQ(s.train.size(), 71u);  // round(70.7)
  EXPECT_EQ(s.validation.size(), 10u);
  EXPECT_EQ(s.test.size(), 20u);
  std::vector<std::size_t> all;
  for (const auto* part : {&s.train, &s.validation, &s.test}) {
    EXPECT_TRUE(std::is_sorted(part->begin(), part->end()));
    all.insert(all.end(), part->begin(), part->end());
  }
  std::sort(all.begin(), all.end());
  for (std::size_t i = 0; i < all.size(); ++i) ASSERT_EQ(all[i], i);
}

TEST(Split, DeterministicPerSeedAndDifferentAcrossSeeds) {
  Rng a(9), b(9), c(10);
  const auto sa = make_random_split(50, {}, a);
  EXPECT_EQ(sa.train, make_random_split(50, {}, b).train);
  EXPECT_NE(sa.train, make_random_split(50, {}, c).train);
}

TEST(Split, OptionsValidated) {
  EXPECT_THROW((SplitOptions{0.0, 0.0}.validate()), OptionError);
  EXPECT_THROW((SplitOptions{1.2, 0.0}.validate()), OptionError);
  EXPECT_THROW((SplitOptions{0.8, 0.3}.validate()), OptionError);
  EXPECT_NO_THROW((SplitOptions{0.8, 0.2}.validate()));
}

}  // namespace
}  // namespace cnclab
