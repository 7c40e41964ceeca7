#pragma once
// Statistics over repeats for `cnclab compare --group-by`: the mean with its
// Student-t confidence interval, Welch's two-sample t-test, a bootstrap
// interval of the difference of means, and for runs paired by seed the
// paired t-test and the Wilcoxon signed-rank test. The t and normal
// distributions come from Boost.Math (Debian's libboost-dev, header only);
// tests/report/welch_reference.py and paired_reference.py give scipy's
// numbers for the same data.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace cnclab {

// Mean of a sample with its confidence interval
//   mean ± t_{(1+level)/2, n-1} s / sqrt(n),   s² = Σ(x - mean)² / (n - 1),
// the interval scipy.stats.t.interval(level, n - 1, mean, s / sqrt(n)) gives.
// n = 1: std and the interval are NaN (no spread to measure); n = 0: all NaN.
struct SampleSummary {
  std::size_t n = 0;
  double mean = 0, std = 0;        // std: sample standard deviation (n - 1)
  double ci_low = 0, ci_high = 0;  // at `level`
};
SampleSummary summarize(const std::vector<double>& x, double level = 0.95);

// Student's t distribution with `df` > 0 degrees of freedom (not necessarily
// whole: Welch's df is not).
double student_t_cdf(double t, double df);
double student_t_quantile(double p, double df);  // p in (0, 1)

// Welch's unequal-variance t-test of mean(b) - mean(a) against 0:
//   se² = s_a²/n_a + s_b²/n_b,   t = (mean_b - mean_a) / se,
//   df = se⁴ / ((s_a²/n_a)² / (n_a - 1) + (s_b²/n_b)² / (n_b - 1))   (Welch–Satterthwaite),
//   p = 2 (1 - F_df(|t|))   (two-sided).
// scipy.stats.ttest_ind(b, a, equal_var=False) gives the same t and p.
// Fewer than 2 values in a group, or no spread in either (se = 0): t, df and
// p are NaN (the test is undefined), difference stays the difference.
struct WelchTest {
  double difference = 0;  // mean(b) - mean(a)
  double t = 0, df = 0, p_value = 0;
};
WelchTest welch_t_test(const std::vector<double>& a, const std::vector<double>& b);

// Paired t-test of b - a over pairs (a[i], b[i]) (runs with the same seed):
//   d_i = b_i - a_i,   t = mean(d) / (s_d / sqrt(n)),   df = n - 1,
//   p = 2 F_df(-|t|)   (two-sided),
// as scipy.stats.ttest_rel(b, a). Fewer than 2 pairs or no spread in d
// (s_d = 0): t and p are NaN. std::invalid_argument on unequal sizes.
struct PairedTTest {
  std::size_t pairs = 0;
  double difference = 0;  // mean(d)
  double t = 0, df = 0, p_value = 0;
};
PairedTTest paired_t_test(const std::vector<double>& a, const std::vector<double>& b);

// Wilcoxon signed-rank test of the pairs' differences d_i = b_i - a_i
// (two-sided; Wilcoxon 1945), as scipy.stats.wilcoxon(b, a) with its
// defaults zero_method "wilcox" and correction False:
//   zero differences are dropped (n: those left); |d| ranked 1..n, ties
//   sharing their average rank; W+ (W-) the sum of the ranks of d > 0 (< 0);
//   statistic W = min(W+, W-).
//   p, n <= 50 and no ties: exact, from the distribution of W+ over the 2^n
//     equally likely sign patterns (counted by dynamic programming):
//     p = min(1, 2 min(P(W+ <= w+), P(W+ >= w+))), 1 at the centre.
//   p, ties or n > 50: normal approximation with the tie correction,
//     z = (W - n(n+1)/4) / sqrt(n(n+1)(2n+1)/24 - Σ(t³ - t)/48)
//     (t: the size of each group of tied |d|), p = 2 Φ(-|z|): scipy's
//     method "approx".
// Where scipy's default differs: with ties and n <= 50 it uses its exact
// table anyway (truncating the half ranks), which does not hold with ties;
// with zero differences it switches to the approximation, where dropping
// them leaves n fair signs, whose exact distribution still holds.
// No non-zero difference: W and p are NaN.
struct WilcoxonTest {
  std::size_t n = 0;  // non-zero differences
  double w = 0;       // min(W+, W-)
  double p_value = 0;
  bool exact = false;  // p from the exact distribution
};
WilcoxonTest wilcoxon_signed_rank(const std::vector<double>& a, const std::vector<double>& b);

// Percentile bootstrap of mean(b) - mean(a): `resamples` times, each group
// resampled with replacement to its own size (Efron & Tibshirani 1993, Ch.
// 13); the interval is the (1 - level)/2 and (1 + level)/2 quantiles of the
// resampled differences (linear interpolation between order statistics, as
// numpy.quantile's default). Seeded: the same inputs and options give the
// same interval.
struct BootstrapOptions {
  std::size_t resamples = 10000;  // >= 100
  std::uint64_t seed = 20260212;  // Rng stream "bootstrap" of this master seed
  double level = 0.95;            // in (0, 1)
  void validate() const;          // OptionError naming the field
};
struct Interval {
  double low = 0, high = 0;
};
// Both groups need at least one value (else NaN).
Interval bootstrap_difference_ci(const std::vector<double>& a, const std::vector<double>& b,
                                 const BootstrapOptions& options = {});

// Quantile q in [0, 1] of sorted values by linear interpolation between order
// statistics: position q (n - 1) (numpy.quantile, method "linear").
double sorted_quantile(const std::vector<double>& sorted, double q);

}  // namespace cnclab
