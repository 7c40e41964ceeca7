#pragma once
// Statistics over repeats for `cnclab compare --group-by`: the mean with its
// Student-t confidence interval, Welch's two-sample t-test and a bootstrap
// interval of the difference of means. The t distribution comes from
// Boost.Math (students_t_distribution: Debian's libboost-dev, header only);
// tests/report/welch_reference.py gives scipy's numbers for the same data.
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
