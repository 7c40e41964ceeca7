// The step-error notes' claims over seeds (step_error_seed_notes.hpp): a
// difference is stated only when Welch's two-sided p is below 0.05. Checked
// on two seeds per setting, where Welch's test has a closed form: with
// a = {0, 2} and b = {d, d + 2} both variances are 2, se = sqrt(2),
// t = d / sqrt(2), df = 2, and the t distribution with 2 degrees of freedom
// has F(t) = 1/2 + t / (2 sqrt(2 + t²)), so p = 1 - |t| / sqrt(2 + t²).
// p = 0.05 at |t| = t_{0.975, 2} = 4.302653, d = 6.084887: d = 6.0 is just
// not significant, d = 6.2 just is.
#include "cnclab/studies/step_error/step_error_seed_notes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace cnclab {
namespace {

constexpr double kPTol = 1e-9;

double closed_form_p(double d) {
  const double t = d / std::sqrt(2.0);
  return 1.0 - std::abs(t) / std::sqrt(2.0 + t * t);
}

SeedSample pair_at(const std::string& label, double d) {
  return {label, {d, d + 2}};
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(StepErrorSeedNotes, SignificanceFollowsTheClosedFormOnBothSidesOfAlpha) {
  for (double d : {1.0, 6.0, 6.2, 10.0}) {
    const SeedComparison c = compare_seeds(pair_at("a", 0), pair_at("b", d));
    EXPECT_NEAR(c.welch.df, 2.0, kPTol) << d;
    EXPECT_NEAR(c.welch.p_value, closed_form_p(d), kPTol) << d;
    EXPECT_EQ(c.significant, closed_form_p(d) < 0.05) << d;
    EXPECT_NEAR(c.a.mean, 1.0, kPTol);
    EXPECT_NEAR(c.b.std, std::sqrt(2.0), kPTol);
  }
  EXPECT_FALSE(compare_seeds(pair_at("a", 0), pair_at("b", 6.0)).significant);
  EXPECT_TRUE(compare_seeds(pair_at("a", 0), pair_at("b", 6.2)).significant);
}

TEST(StepErrorSeedNotes, SentenceStatesADifferenceOnlyWhenSignificant) {
  // d = 10: p = 1 - 7.0711 / sqrt(52) = 0.019419.
  const std::string yes =
      seed_difference_sentence("mean |e|", pair_at("refit", 0), pair_at("keep", 10), 3);
  EXPECT_TRUE(contains(yes, "refit 1.000 ± 1.414 is lower than keep 11.000 ± 1.414")) << yes;
  EXPECT_TRUE(contains(yes, "Welch p = 0.019 < 0.05")) << yes;
  EXPECT_FALSE(contains(yes, "seed noise")) << yes;
  // Reversed order: "higher".
  const std::string higher =
      seed_difference_sentence("mean |e|", pair_at("keep", 10), pair_at("refit", 0), 3);
  EXPECT_TRUE(contains(higher, "keep 11.000 ± 1.414 is higher than refit")) << higher;
  // d = 1: p = 1 - 0.70711 / sqrt(2.5) = 0.55279.
  const std::string no =
      seed_difference_sentence("mean |e|", pair_at("refit", 0), pair_at("keep", 1), 3);
  EXPECT_TRUE(contains(no, "not distinguishable from seed noise")) << no;
  EXPECT_TRUE(contains(no, "Welch p = 0.55 ≥ 0.05")) << no;
  EXPECT_FALSE(contains(no, "lower")) << no;
}

TEST(StepErrorSeedNotes, UndefinedTestIsNotADifference) {
  const std::string same =
      seed_difference_sentence("x", {"a", {1, 1}}, {"b", {2, 2}}, 1);  // no spread
  EXPECT_TRUE(contains(same, "not distinguishable")) << same;
  EXPECT_TRUE(contains(same, "undefined")) << same;
}

TEST(StepErrorSeedNotes, LowestMeanIsTheBestOnlyBeyondSeedNoise) {
  // Lowest mean 1 (p = 0.9), next 11 (p = 0.8): d = 10, significant.
  const std::string best = lowest_mean_sentence(
      "test MSE", {pair_at("p = 0.8", 10), pair_at("p = 0.9", 0), pair_at("p = 0.3", 20)}, 3);
  EXPECT_TRUE(contains(best, "lowest mean at p = 0.9 (1.000 ± 1.414)")) << best;
  EXPECT_TRUE(contains(best, "the next, p = 0.8 (11.000 ± 1.414)")) << best;
  EXPECT_TRUE(contains(best, "p = 0.9 is the best")) << best;
  // Next only 1 above: p = 0.55, no best; a one-seed setting with a lower
  // value takes no part.
  const std::string none = lowest_mean_sentence(
      "test MSE", {pair_at("p = 0.8", 1), pair_at("p = 0.9", 0), {"p = 0.4", {-5}}}, 3);
  EXPECT_TRUE(contains(none, "lowest mean at p = 0.9")) << none;
  EXPECT_TRUE(contains(none, "not distinguishable from the next, p = 0.8")) << none;
  EXPECT_TRUE(contains(none, "no single best")) << none;
  EXPECT_FALSE(contains(none, "p = 0.4")) << none;
  EXPECT_EQ(lowest_mean_sentence("x", {pair_at("a", 0), {"b", {1}}}, 3), "");
}

}  // namespace
}  // namespace cnclab
