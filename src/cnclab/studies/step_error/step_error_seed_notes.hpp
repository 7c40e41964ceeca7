#pragma once
// The step-error tables' claims about differences between settings (Table
// 2's best keep probability p, keeping vs refitting the normaliser), made
// only where the seeds support them: Welch's two-sample t-test
// (report/statistics.hpp) over the per-seed values of two settings; a
// difference is stated when its two-sided p-value is below alpha, otherwise
// the sentence says it is not distinguishable from seed noise. Each sentence
// carries both means ± std (n - 1) and the p-value.
#include <string>
#include <vector>

#include "cnclab/report/statistics.hpp"

namespace cnclab {

inline constexpr double kSeedAlpha = 0.05;  // significance level of the tables' notes

// One setting's values over its seeds.
struct SeedSample {
  std::string label;           // "p = 0.5", "refit"
  std::vector<double> values;  // one per seed (finite)
};

struct SeedComparison {
  SampleSummary a, b;
  WelchTest welch;           // mean(b) - mean(a)
  bool significant = false;  // welch.p_value < alpha; false when the test is undefined
};
SeedComparison compare_seeds(const SeedSample& a, const SeedSample& b, double alpha = kSeedAlpha);

// "0.070 ± 0.003"; a single seed has no spread: "0.070 (1 seed)".
std::string seed_mean_std_text(const SampleSummary& s, int decimals);

// "mean |e| (µm), surface 2: refit 0.070 ± 0.003 is lower than keep 0.098 ±
// 0.004 (5 and 5 seeds; Welch p = 0.00012 < 0.05)." or "...: refit 0.070 ±
// 0.003 and keep 0.071 ± 0.004 are not distinguishable from seed noise (5
// and 5 seeds; Welch p = 0.43 ≥ 0.05)." `decimals`: of the means and stds.
std::string seed_difference_sentence(const std::string& what, const SeedSample& a,
                                     const SeedSample& b, int decimals, double alpha = kSeedAlpha);

// Table 2 over seeds: the setting with the lowest mean (test MSE) against
// the next lowest, stated as the best only when Welch's test separates the
// two. Settings with fewer than 2 seeds take no part; "" when fewer than
// two settings remain.
std::string lowest_mean_sentence(const std::string& what, const std::vector<SeedSample>& samples,
                                 int decimals, double alpha = kSeedAlpha);

}  // namespace cnclab
