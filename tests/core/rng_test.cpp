#include "cnclab/core/rng.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace cnclab {
namespace {

TEST(Rng, SameSeedGivesSameStream) {
  Rng a(123), b(123);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(a.next_u64(), b.next_u64());
}

TEST(Rng, NamedStreamsAreIndependentOfEachOther) {
  EXPECT_NE(derive_seed(7, "split"), derive_seed(7, "init"));
  EXPECT_NE(derive_seed(7, "split"), derive_seed(8, "split"));
  EXPECT_EQ(derive_seed(7, "split"), derive_seed(7, "split"));
}

TEST(Rng, UniformMomentsMatchTheory) {
  Rng rng(42);
  constexpr int kN = 200000;
  double sum = 0, sum2 = 0;
  for (int i = 0; i < kN; ++i) {
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    sum += u;
    sum2 += u * u;
  }
  const double mean = sum / kN, var = sum2 / kN - mean * mean;
  // Mean 1/2, variance 1/12; 5-sigma bounds on the sample estimates.
  EXPECT_NEAR(mean, 0.5, 5 * std::sqrt(1.0 / 12 / kN));
  EXPECT_NEAR(var, 1.0 / 12, 5e-3);
}

TEST(Rng, NormalMomentsMatchTheory) {
  Rng rng(43);
  constexpr int kN = 200000;
  double sum = 0, sum2 = 0, sum4 = 0;
  for (int i = 0; i < kN; ++i) {
    const double z = rng.normal(2.0, 3.0);
    sum += z;
    sum2 += (z - 2.0) * (z - 2.0);
    sum4 += std::pow((z - 2.0) / 3.0, 4);
  }
  EXPECT_NEAR(sum / kN, 2.0, 5 * 3.0 / std::sqrt(kN));
  EXPECT_NEAR(std::sqrt(sum2 / kN), 3.0, 0.03);
  EXPECT_NEAR(sum4 / kN, 3.0, 0.1);  // kurtosis of a normal distribution
}

TEST(Rng, BelowIsUnbiasedAndInRange) {
  Rng rng(44);
  constexpr int kN = 70000;
  int counts[7] = {};
  for (int i = 0; i < kN; ++i) {
    const auto k = rng.below(7);
    ASSERT_LT(k, 7u);
    ++counts[k];
  }
  // Chi-square with 6 degrees of freedom; 22.46 is the 0.999 quantile.
  double chi2 = 0;
  for (int c : counts) chi2 += std::pow(c - kN / 7.0, 2) / (kN / 7.0);
  EXPECT_LT(chi2, 22.46);
}

TEST(Rng, ShuffleIsAPermutation) {
  Rng rng(45);
  std::vector<int> v(100);
  for (int i = 0; i < 100; ++i) v[i] = i;
  rng.shuffle(v);
  std::vector<int> sorted = v;
  std::sort(sorted.begin(), sorted.end());
  for (int i = 0; i < 100; ++i) ASSERT_EQ(sorted[i], i);
  EXPECT_NE(v, sorted);
}

}  // namespace
}  // namespace cnclab
