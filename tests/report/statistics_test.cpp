// Statistics over repeats (report/statistics.hpp) against scipy 1.10.1:
// the numbers below are the output of
//   /usr/bin/python3 tests/report/welch_reference.py
// (scipy.stats.ttest_ind(b, a, equal_var=False), t.interval, t.ppf, t.cdf
// on the same fixed data; one tail quantile also to 40 digits with mpmath),
// and of
//   /usr/bin/python3 tests/report/paired_reference.py
// (scipy.stats.ttest_rel and scipy.stats.wilcoxon). The bootstrap is checked
// by its properties, the Wilcoxon distribution also by enumeration.
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

constexpr double kScipyTol = 1e-9;  // scipy's numbers to 1e-9

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

// paired_reference.py's 60 pairs (numpy seed 7, rounded to 6 digits).
const std::vector<double> kPairsA = {
    1.000123, 1.029875, 0.972586, 0.910941, 0.954533, 0.900835, 1.006014, 1.134022, 0.950779,
    0.937953, 1.048984, 1.035689, 1.010541, 0.906953, 0.997075, 1.06953,  0.865579, 0.954238,
    0.809878, 0.871046, 0.815826, 0.976491, 0.873255, 1.027126, 1.015675, 0.981307, 0.748324,
    0.946131, 0.99515,  1.011331, 0.846986, 0.952225, 0.902148, 0.919116, 1.10609,  0.919247,
    0.996748, 1.088439, 0.94164,  0.98883,  1.011046, 1.006378, 0.877494, 1.007614, 1.135882,
    0.845286, 1.085938, 1.011935, 0.935853, 1.200042, 1.076226, 0.880071, 1.007452, 1.057669,
    0.981122, 1.068291, 0.993348, 1.066725, 1.143852, 0.932434};
const std::vector<double> kPairsB = {
    1.03028,  1.02671,  0.998949, 0.871581, 0.945568, 0.911025, 1.070952, 1.211283, 0.904603,
    0.918221, 1.101329, 0.956068, 1.007383, 0.922089, 1.079926, 1.124,    0.869218, 0.955809,
    0.817368, 0.967222, 0.814425, 0.981307, 0.910884, 1.041087, 1.025811, 0.945604, 0.767748,
    0.943952, 1.073456, 1.063985, 0.865779, 1.005644, 0.905155, 0.991722, 1.12582,  0.968416,
    0.952203, 1.125773, 0.87723,  0.907064, 1.015822, 0.981382, 0.905697, 1.139852, 1.114296,
    0.834089, 1.116208, 1.056586, 0.947033, 1.209745, 1.131349, 0.926066, 0.975768, 1.07371,
    1.002886, 1.035567, 1.02634,  1.043827, 1.212455, 0.962071};

struct ScipyPaired {
  std::string name;
  std::vector<double> a, b;
  double t, df, p, w, w_p;
  bool exact;  // the Wilcoxon p from the exact distribution
};

// paired_reference.py's output (scipy 1.10.1): ttest_rel(b, a), wilcoxon(b,
// a) (with ties: method "approx"; with zeros: over the non-zero pairs).
const std::vector<ScipyPaired> kScipyPaired = {
    {"exact5",
     {0.81, 0.92, 0.77, 0.88, 0.95},
     {0.71, 0.95, 0.70, 0.74, 0.66},
     -2.1834433352480631,
     4,
     0.094380638895085911,
     1,
     0.125,
     true},
    {"exact8",
     {5.1, 4.8, 6.0, 5.5, 5.9, 4.7, 5.3, 6.2},
     {5.6, 5.0, 6.15, 6.35, 5.8, 5.4, 5.95, 7.15},
     3.7257691732316682,
     7,
     0.0073997465896591891,
     1,
     0.015625,
     true},
    {"ties",
     {1.0, 2.0, 3.0, 4.0, 5.0, 6.0},
     {1.5, 2.5, 2.5, 4.25, 5.75, 6.5},
     1.8650096164806276,
     5,
     0.12118808449938513,
     3.5,
     0.13113050286965086,
     false},
    {"zeros",
     {1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0},
     {1.0, 2.3, 2.6, 4.0, 5.9, 6.8, 8.1},
     1.82867074599221,
     6,
     0.11720380648475485,
     2,
     0.1875,
     true},
    {"n60", kPairsA, kPairsB, 2.904036732533644, 59, 0.0051761912005264584, 530,
     0.0045938103773031456, false},
};

TEST(Statistics, PairedTestsMatchScipy) {
  for (const auto& s : kScipyPaired) {
    const PairedTTest t = paired_t_test(s.a, s.b);
    EXPECT_EQ(t.pairs, s.a.size()) << s.name;
    EXPECT_NEAR(t.t, s.t, kScipyTol) << s.name;
    EXPECT_EQ(t.df, s.df) << s.name;
    EXPECT_NEAR(t.p_value, s.p, kScipyTol) << s.name;
    const WilcoxonTest w = wilcoxon_signed_rank(s.a, s.b);
    EXPECT_EQ(w.w, s.w) << s.name;
    EXPECT_NEAR(w.p_value, s.w_p, kScipyTol) << s.name;
    EXPECT_EQ(w.exact, s.exact) << s.name;
  }
  EXPECT_EQ(wilcoxon_signed_rank(kScipyPaired[3].a, kScipyPaired[3].b).n, 5u);  // 2 zeros dropped
}

// The exact distribution against enumeration of all 2^n sign patterns: the
// p of every possible W+ at n = 6 (64 patterns).
TEST(Statistics, WilcoxonExactPIsTheShareOfSignPatterns) {
  constexpr int n = 6;
  std::vector<int> count(n * (n + 1) / 2 + 1, 0);
  for (int signs = 0; signs < (1 << n); ++signs) {
    int w = 0;
    for (int k = 0; k < n; ++k) w += (signs >> k & 1) ? k + 1 : 0;
    ++count[static_cast<std::size_t>(w)];
  }
  for (int plus_mask = 0; plus_mask < (1 << n); ++plus_mask) {
    // Differences ±(k+1): ranks 1..n, positive where the mask says.
    std::vector<double> a(n, 0.0), b(n);
    int w = 0;
    for (int k = 0; k < n; ++k) {
      const bool plus = plus_mask >> k & 1;
      b[static_cast<std::size_t>(k)] = plus ? k + 1 : -(k + 1);
      w += plus ? k + 1 : 0;
    }
    double below = 0, above = 0;
    for (int v = 0; v <= w; ++v) below += count[static_cast<std::size_t>(v)];
    for (int v = w; v < static_cast<int>(count.size()); ++v)
      above += count[static_cast<std::size_t>(v)];
    const double expected =
        2 * w == n * (n + 1) / 2 ? 1.0 : std::min(1.0, 2 * std::min(below, above) / (1 << n));
    const WilcoxonTest t = wilcoxon_signed_rank(a, b);
    ASSERT_TRUE(t.exact);
    EXPECT_NEAR(t.p_value, expected, 1e-15) << "W+ = " << w;
    EXPECT_EQ(t.w, std::min(w, n * (n + 1) / 2 - w));
  }
}

TEST(Statistics, PairedUndefinedCasesAreNaN) {
  EXPECT_TRUE(std::isnan(paired_t_test({1.0}, {2.0}).p_value));
  const PairedTTest same_shift = paired_t_test({1.0, 2.0, 3.0}, {1.5, 2.5, 3.5});  // s_d = 0
  EXPECT_TRUE(std::isnan(same_shift.p_value));
  EXPECT_EQ(same_shift.difference, 0.5);
  const WilcoxonTest equal = wilcoxon_signed_rank({1.0, 2.0}, {1.0, 2.0});
  EXPECT_EQ(equal.n, 0u);
  EXPECT_TRUE(std::isnan(equal.p_value));
  EXPECT_THROW(paired_t_test({1.0}, {1.0, 2.0}), std::invalid_argument);
}

}  // namespace
}  // namespace cnclab
