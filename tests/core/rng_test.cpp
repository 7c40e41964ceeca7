#include "cnclab/core/rng.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "cnclab/core/error.hpp"

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

// The message of the ConfigError parse_seed throws, or "accepted".
std::string seed_error(const std::string& text) {
  try {
    parse_seed(text, "--seed");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(ParseSeed, AcceptsEveryUnsigned64BitDecimal) {
  EXPECT_EQ(parse_seed("0", "--seed"), 0u);
  EXPECT_EQ(parse_seed("42", "--seed"), 42u);
  EXPECT_EQ(parse_seed("+7", "--seed"), 7u);
  EXPECT_EQ(parse_seed("007", "--seed"), 7u);
  EXPECT_EQ(parse_seed("18446744073709551615", "--seed"),
            std::numeric_limits<std::uint64_t>::max());
}

TEST(ParseSeed, RejectsNegativeNonIntegerAndOversizedValuesNamingOptionAndValue) {
  // strtoull("-1") is 2^64 - 1: the value the command line used to run with.
  EXPECT_EQ(seed_error("-1"),
            "--seed -1: expected a non-negative integer (0 to 18446744073709551615)");
  for (const char* text : {"-0", "1.5", "1e3", "0x10", "seven", " 1", "1 ", "+", "--1"}) {
    EXPECT_EQ(
        seed_error(text).find(std::string("--seed ") + text + ": expected a non-negative integer"),
        0u)
        << text;
  }
  EXPECT_EQ(seed_error(""),
            "--seed '': expected a non-negative integer (0 to 18446744073709551615)");
  EXPECT_EQ(seed_error("18446744073709551616"),
            "--seed 18446744073709551616: integer too large (0 to 18446744073709551615)");
  EXPECT_NE(seed_error("99999999999999999999999").find("integer too large"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
