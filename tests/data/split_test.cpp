#include "cnclab/data/split.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

// Disjoint, covering 0..n-1, each part sorted.
void expect_partition(const Split& s, std::size_t n) {
  std::vector<std::size_t> all;
  for (const auto* part : {&s.train, &s.validation, &s.test}) {
    EXPECT_TRUE(std::is_sorted(part->begin(), part->end()));
    all.insert(all.end(), part->begin(), part->end());
  }
  std::sort(all.begin(), all.end());
  ASSERT_EQ(all.size(), n);
  for (std::size_t i = 0; i < n; ++i) ASSERT_EQ(all[i], i);
}

TEST(Split, DisjointCoveringSortedWithRoundedSizes) {
  struct Case {
    std::size_t n;
    double train, validation;
    std::size_t n_train, n_validation;
  };
  // Sizes by hand: round half away from zero.
  for (const Case c : {Case{101, 0.7, 0.1, 71, 10},  // 70.7 -> 71, 10.1 -> 10
                       Case{10, 0.25, 0.25, 3, 3},   // 2.5 -> 3, 2.5 -> 3
                       Case{10, 0.7, 0.3, 7, 3},     // whole set, empty test
                       Case{3, 1.0, 0.0, 3, 0}, Case{1, 0.7, 0.0, 1, 0}, Case{0, 0.7, 0.1, 0, 0},
                       Case{1000, 0.7, 0.15, 700, 150}}) {
    Rng rng(5);
    const Split s = make_random_split(c.n, {c.train, c.validation}, rng);
    EXPECT_EQ(s.train.size(), c.n_train) << c.n;
    EXPECT_EQ(s.validation.size(), c.n_validation) << c.n;
    EXPECT_EQ(s.test.size(), c.n - c.n_train - c.n_validation) << c.n;
    expect_partition(s, c.n);
  }
}

TEST(Split, DeterministicPerSeedAndDifferentAcrossSeeds) {
  Rng a(9), b(9), c(10);
  const auto sa = make_random_split(50, {0.6, 0.2}, a);
  const auto sb = make_random_split(50, {0.6, 0.2}, b);
  EXPECT_EQ(sa.train, sb.train);
  EXPECT_EQ(sa.validation, sb.validation);
  EXPECT_EQ(sa.test, sb.test);
  EXPECT_NE(sa.train, make_random_split(50, {0.6, 0.2}, c).train);
}

// Each index lands in the training part with probability train_fraction:
// over many seeds the count for one index is binomial.
TEST(Split, EveryIndexIsEquallyLikelyInTraining) {
  constexpr std::size_t kN = 10, kTrials = 4000;
  std::vector<int> count(kN, 0);
  for (std::size_t t = 0; t < kTrials; ++t) {
    Rng rng(1000 + t);
    for (const auto i : make_random_split(kN, {0.3, 0.0}, rng).train) ++count[i];
  }
  const double mean = 0.3 * kTrials;
  const double sd = std::sqrt(kTrials * 0.3 * 0.7);
  for (std::size_t i = 0; i < kN; ++i) EXPECT_NEAR(count[i], mean, 5 * sd) << i;
}

TEST(Split, OptionsValidated) {
  EXPECT_NO_THROW((SplitOptions{0.0, 0.0}.validate()));  // evaluation only: all samples test
  EXPECT_THROW((SplitOptions{-0.1, 0.0}.validate()), OptionError);
  EXPECT_THROW((SplitOptions{1.2, 0.0}.validate()), OptionError);
  EXPECT_THROW((SplitOptions{std::nan(""), 0.0}.validate()), OptionError);
  EXPECT_THROW((SplitOptions{0.5, -0.1}.validate()), OptionError);
  try {
    SplitOptions{0.8, 0.3}.validate();
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "validation_fraction");
    EXPECT_NE(e.rule().find("must not exceed 1"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW((SplitOptions{0.8, 0.2}.validate()));
  EXPECT_NO_THROW((SplitOptions{}.validate()));
  Rng rng(1);
  EXPECT_THROW(make_random_split(10, {-0.1, 0.0}, rng), OptionError);
  const Split all_test = make_random_split(10, {0.0, 0.0}, rng);
  EXPECT_TRUE(all_test.train.empty());
  EXPECT_EQ(all_test.test.size(), 10u);
}

}  // namespace
}  // namespace cnclab

namespace cnclab {
namespace {

SplitOptions counts(std::optional<std::size_t> train, std::optional<std::size_t> validation,
                    std::optional<std::size_t> test) {
  SplitOptions o;
  o.train_count = train;
  o.validation_count = validation;
  o.test_count = test;
  return o;
}

// Seed 004 Sec. 4.2: 1042 training, 1040 test, the rest (1043) validation.
TEST(SplitCounts, Seed004TextGivesTheRestToValidation) {
  Rng rng(1);
  const Split s = make_random_split(3125, counts(1042, std::nullopt, 1040), rng);
  EXPECT_EQ(s.train.size(), 1042u);
  EXPECT_EQ(s.test.size(), 1040u);
  EXPECT_EQ(s.validation.size(), 1043u);
  expect_partition(s, 3125);
}

TEST(SplitCounts, AbsentPartTakesTheRest) {
  Rng rng(2);
  const Split a = make_random_split(10, counts(4, 3, std::nullopt), rng);
  EXPECT_EQ(a.validation.size(), 3u);
  EXPECT_EQ(a.test.size(), 3u);
  const Split b = make_random_split(10, counts(4, std::nullopt, std::nullopt), rng);
  EXPECT_EQ(b.validation.size(), 0u);
  EXPECT_EQ(b.test.size(), 6u);
  const Split c = make_random_split(10, counts(4, 5, 1), rng);
  EXPECT_EQ(c.test.size(), 1u);
  expect_partition(c, 10);
}

// Table 5's 1042 / 1042 / 348 adds up to 2432, not 3125: refused.
TEST(SplitCounts, CountsThatDoNotFitAreErrorsNamingTheCount) {
  try {
    counts(1042, 348, 1042).validate_for(3125);
    FAIL();
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "test_count");
    EXPECT_NE(std::string(e.what()).find("2432 for 3125 samples"), std::string::npos) << e.what();
  }
  EXPECT_THROW(counts(2000, std::nullopt, 2000).validate_for(3125), OptionError);
  // No training samples is a valid split (evaluation-only experiments); it
  // still has to fit the samples.
  EXPECT_NO_THROW(counts(0, std::nullopt, 1).validate_for(1));
  EXPECT_THROW(counts(0, std::nullopt, 2).validate_for(1), OptionError);
  EXPECT_THROW(counts(std::nullopt, std::nullopt, 5).validate(), OptionError);
  EXPECT_NO_THROW(counts(3125, std::nullopt, std::nullopt).validate_for(3125));
}

}  // namespace
}  // namespace cnclab
