// Statistics over repeats (report/statistics.hpp) against scipy 1.10.1:
// the numbers below are the output of
//   /usr/bin/python3 tests/report/welch_reference.py
// (scipy.stats.ttest_ind(b, a, equal_var=False), t.interval, t.ppf, t.cdf
// on the same fixed data; one tail quantile also to 40 digits with mpmath).
// The bootstrap is checked by its properties.
#include "cnclab/report/statistics.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"

namespace cnclab {
namespace {

constexpr double kScipyTol = 1e-9;  // issue 20: match scipy to 1e-9

struct Case {
  std::string name;
  std::vector<double> a, b;
};

// The data of welch_reference.py's CASES, in its order.
const std::vector<Case> kCases = {
    {"equal_sizes", {0.82, 0.91, 0.77, 0.88, 0.95}, {0.71, 0.69, 0.80, 0.74, 0.66}},
    {"unequal", {5.81, 6.02, 5.33, 6.44, 5.47}, {6.58, 7.91, 5.12, 6.10, 7.40, 6.95, 5.88}},
    {"small_p", {1.0, 1.1, 0.9, 1.05, 0.95, 1.02}, {2.0, 2.3, 1.8, 2.1, 2.2}},
    {"two_values", {3.0, 3.5}, {2.0, 2.2, 2.1, 2.6}},
};

struct ScipyWelch {
  std::string name;
  double t, df, p, a_low, a_high, b_low, b_high;
};

// welch_reference.py's output (scipy 1.10.1).
const std::vector<ScipyWelch> kScipy = {
    {"equal_sizes", -3.6545710725488374, 7.3962264150943424, 0.0073868504029025433,
     0.77706703504800134, 0.95493296495199864, 0.65371328164224163, 0.78628671835775854},
    {"unequal", 1.8238381497097349, 8.9632456891598835, 0.10161957739244924, 5.2632691751200316,
     6.3647308248799668, 5.6831880907831183, 7.4425261949311681},
    {"small_p", 11.857703036161791, 4.9138107996665603, 8.3989684197136879e-05, 0.92863395698730089,
     1.0780327096793654, 1.8411611611900012, 2.3188388388099979},
    {"two_values", -3.628650138505535, 1.5893264087775245, 0.095086358581546834,
     0.07344881589197616, 6.4265511841080238, 1.8065153695724874, 2.6434846304275128},
};

TEST(Statistics, WelchMatchesScipy) {
  ASSERT_EQ(kCases.size(), kScipy.size());
  for (std::size_t i = 0; i < kCases.size(); ++i) {
    const Case& c = kCases[i];
    const ScipyWelch& s = kScipy[i];
    ASSERT_EQ(c.name, s.name);
    const WelchTest w = welch_t_test(c.a, c.b);
    EXPECT_NEAR(w.t, s.t, kScipyTol) << c.name;
    EXPECT_NEAR(w.df, s.df, kScipyTol) << c.name;
    EXPECT_NEAR(w.p_value, s.p, kScipyTol) << c.name;
    EXPECT_NEAR(w.p_value / s.p, 1.0, 1e-8) << c.name;  // relative too: small_p is 8.4e-5
    const SampleSummary a = summarize(c.a), b = summarize(c.b);
    EXPECT_NEAR(a.ci_low, s.a_low, kScipyTol) << c.name;
    EXPECT_NEAR(a.ci_high, s.a_high, kScipyTol) << c.name;
    EXPECT_NEAR(b.ci_low, s.b_low, kScipyTol) << c.name;
    EXPECT_NEAR(b.ci_high, s.b_high, kScipyTol) << c.name;
    EXPECT_NEAR(w.difference, b.mean - a.mean, 1e-15) << c.name;
  }
}

TEST(Statistics, StudentTMatchesScipy) {
  // {p, df, scipy.stats.t.ppf(p, df)}
  const std::vector<std::array<double, 3>> ppf = {{0.975, 4, 2.7764451051977987},
                                                  {0.975, 7.3, 2.3450667361509292},
                                                  {0.6, 30, 0.2556053644420514}};
  for (const auto& [p, df, q] : ppf) EXPECT_NEAR(student_t_quantile(p, df), q, kScipyTol);
  // welch_reference.py's mpmath line: t.ppf(0.995, 2.5) to 20 digits (scipy
  // is 4.9e-9 off there).
  EXPECT_NEAR(student_t_quantile(0.995, 2.5), 7.1637281389487855199, 1e-13);
  // {t, df, scipy.stats.t.cdf(t, df)}
  const std::vector<std::array<double, 3>> cdf = {{-2.1, 4, 0.051826643158801089},
                                                  {0.3, 7.3, 0.6137297319101449},
                                                  {3.7, 2.5, 0.97681521653906478},
                                                  {-0.05, 100, 0.48011106087098709}};
  for (const auto& [t, df, f] : cdf) EXPECT_NEAR(student_t_cdf(t, df), f, kScipyTol);
  // Closed form at df = 1 (Cauchy): F(t) = 1/2 + atan(t)/pi.
  for (double t : {-3.0, -0.5, 0.0, 1.7}) {
    EXPECT_NEAR(student_t_cdf(t, 1), 0.5 + std::atan(t) / std::numbers::pi, 1e-14);
  }
}

TEST(Statistics, UndefinedCasesAreNaN) {
  const SampleSummary one = summarize({2.5});
  EXPECT_EQ(one.mean, 2.5);
  EXPECT_TRUE(std::isnan(one.std) && std::isnan(one.ci_low) && std::isnan(one.ci_high));
  EXPECT_TRUE(std::isnan(summarize({}).mean));
  const WelchTest few = welch_t_test({1.0}, {2.0, 3.0});
  EXPECT_EQ(few.difference, 1.5);
  EXPECT_TRUE(std::isnan(few.t) && std::isnan(few.p_value));
  // No spread in either group: the test is undefined (scipy also gives nan).
  const WelchTest flat = welch_t_test({1.0, 1.0, 1.0}, {2.0, 2.0});
  EXPECT_TRUE(std::isnan(flat.p_value));
  EXPECT_EQ(flat.difference, 1.0);
}

TEST(Statistics, QuantileInterpolatesLikeNumpy) {
  const std::vector<double> v = {1, 2, 4, 8};
  EXPECT_EQ(sorted_quantile(v, 0), 1);
  EXPECT_EQ(sorted_quantile(v, 1), 8);
  EXPECT_NEAR(sorted_quantile(v, 0.5), 3, 1e-15);            // numpy.quantile: 3.0
  EXPECT_NEAR(sorted_quantile(v, 0.25), 1.75, 1e-15);        // position 0.75
  EXPECT_NEAR(sorted_quantile(v, 0.975), 7.7 + 0.0, 1e-12);  // position 2.925
}

std::vector<double> normal_sample(std::uint64_t seed, std::size_t n, double mean) {
  Rng rng(seed, "sample");
  std::vector<double> x(n);
  for (double& v : x) v = rng.normal(mean, 1.0);
  return x;
}

TEST(Statistics, BootstrapIsSeededAndContainsTheDifference) {
  const auto a = normal_sample(1, 10, 0.0), b = normal_sample(2, 10, 0.5);
  BootstrapOptions o;
  const Interval first = bootstrap_difference_ci(a, b, o);
  const Interval again = bootstrap_difference_ci(a, b, o);
  EXPECT_EQ(first.low, again.low);  // same seed, same resamples: identical
  EXPECT_EQ(first.high, again.high);
  const double d = welch_t_test(a, b).difference;
  EXPECT_LT(first.low, d);
  EXPECT_GT(first.high, d);
  o.seed = 7;
  const Interval other = bootstrap_difference_ci(a, b, o);
  EXPECT_NE(other.low, first.low);  // another seed, other resamples
  // A wider level gives a wider interval from the same resamples.
  o.level = 0.99;
  const Interval wide = bootstrap_difference_ci(a, b, o);
  EXPECT_LE(wide.low, other.low);
  EXPECT_GE(wide.high, other.high);
}

TEST(Statistics, BootstrapWidthShrinksWithSampleSize) {
  // The width scales as 1/sqrt(n): 16x the samples, about a quarter of the width.
  const auto width = [](std::size_t n) {
    const Interval i =
        bootstrap_difference_ci(normal_sample(3, n, 0.0), normal_sample(4, n, 1.0), {});
    return i.high - i.low;
  };
  const double w10 = width(10), w160 = width(160);
  EXPECT_LT(w160, 0.5 * w10);
  EXPECT_GT(w160, 0.1 * w10);
  // And it is close to the t interval of the difference for normal data
  // (2 * 1.96 * sqrt(2/n) = 0.438 at n = 160).
  EXPECT_NEAR(w160, 2 * 1.96 * std::sqrt(2.0 / 160), 0.08);
}

TEST(Statistics, BootstrapOptionsAreValidated) {
  BootstrapOptions o;
  o.resamples = 10;
  EXPECT_THROW(o.validate(), OptionError);
  o = {};
  o.level = 1.0;
  EXPECT_THROW(o.validate(), OptionError);
}

}  // namespace
}  // namespace cnclab
