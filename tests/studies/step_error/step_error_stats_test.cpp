// Bin counts, shares and error measures of `cnclab tables step-error`,
// against hand-computed cases and the paper's own Table 3 (counts ->
// printed percentages).
#include "cnclab/studies/step_error/step_error_stats.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr double kTol = 1e-12;

TEST(StepErrorStats, BinsAreHalfOpenWithOverflow) {
  // Table 3's absolute-error edges; values on edges go to the bin they open.
  const std::vector<double> edges = {0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.8};
  const std::vector<double> values = {0, 0.05, 0.1, 0.1999, 0.2, 0.5, 0.79, 0.8, 1.2};
  const BinCounts b = bin_counts(values, edges);
  EXPECT_EQ(b.counts, (std::vector<std::size_t>{2, 2, 1, 0, 0, 2}));
  EXPECT_EQ(b.above, 2u);  // 0.8 and 1.2
  EXPECT_EQ(b.below, 0u);
  EXPECT_EQ(b.total(), values.size());
}

TEST(StepErrorStats, BelowFirstEdgeAndInfiniteLastEdge) {
  const std::vector<double> edges = {1, 5, INFINITY};
  const BinCounts b = bin_counts({-1, 0.5, 1, 4.99, 5, 1e300, INFINITY}, edges);
  EXPECT_EQ(b.below, 2u);
  EXPECT_EQ(b.counts, (std::vector<std::size_t>{2, 2}));
  EXPECT_EQ(b.above, 1u);  // +inf itself: the table folds it into "> 5"
  EXPECT_EQ(b.total(), 7u);
}

TEST(StepErrorStats, RejectsBadEdgesAndNaN) {
  EXPECT_THROW(bin_counts({1.0}, {0.0}), Error);
  EXPECT_THROW(bin_counts({1.0}, {0.0, 0.2, 0.2}), Error);
  EXPECT_THROW(bin_counts({1.0}, {0.0, 0.3, 0.2}), Error);
  EXPECT_THROW(bin_counts({NAN}, {0.0, 1.0}), Error);
}

TEST(StepErrorStats, PercentReproducesPaperTable3) {
  // Seed 000 Table 3: counts of 5,940 test samples and the printed ratios.
  const std::vector<std::size_t> abs_count = {3616, 1629, 440, 206, 32, 17};
  const std::vector<std::string> abs_ratio = {"60.88", "27.42", "7.41", "3.47", "0.54", "0.29"};
  const std::vector<std::size_t> rel_count = {1190, 3363, 774, 187, 109, 317};
  const std::vector<std::string> rel_ratio = {"20.03", "56.62", "13.03", "3.15", "1.84", "5.34"};
  const auto check = [](const std::vector<std::size_t>& count,
                        const std::vector<std::string>& ratio) {
    std::size_t total = 0;
    for (auto c : count) total += c;
    ASSERT_EQ(total, 5940u);
    for (std::size_t k = 0; k < count.size(); ++k) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "%.2f", percent(count[k], total));
      EXPECT_EQ(buf, ratio[k]) << k;
    }
  };
  check(abs_count, abs_ratio);
  check(rel_count, rel_ratio);
  EXPECT_TRUE(std::isnan(percent(0, 0)));
}

TEST(StepErrorStats, Labels) {
  EXPECT_EQ(bin_labels({0, 0.1, 0.2, 0.8}, ""),
            (std::vector<std::string>{"< 0.1", "0.1–0.2", "0.2–0.8"}));
  EXPECT_EQ(bin_labels({0, 1, 5, INFINITY}, "%"),
            (std::vector<std::string>{"< 1 %", "1–5 %", "> 5 %"}));
  EXPECT_EQ(overflow_label({0, 0.5, 0.8}, ""), "≥ 0.8");
}

TEST(StepErrorStats, AbsoluteAndRelativeErrors) {
  const std::vector<double> target = {1.0, 2.0, 0.0, 0.0, 4.0};
  const std::vector<double> predicted = {1.1, 1.5, 0.0, 0.3, 4.0};
  const auto a = absolute_errors(predicted, target);
  const auto r = relative_errors_percent(predicted, target);
  const std::vector<double> a_expected = {0.1, 0.5, 0.0, 0.3, 0.0};
  const std::vector<double> r_expected = {10.0, 25.0, 0.0, INFINITY, 0.0};
  for (std::size_t i = 0; i < target.size(); ++i) {
    EXPECT_NEAR(a[i], a_expected[i], kTol) << i;
    if (std::isinf(r_expected[i])) {
      EXPECT_TRUE(std::isinf(r[i])) << i;
    } else {
      EXPECT_NEAR(r[i], r_expected[i], 1e-9) << i;
    }
  }
  EXPECT_THROW(absolute_errors({1.0}, {1.0, 2.0}), Error);
}

TEST(StepErrorStats, FiguresAndShares) {
  // |e| = 0.2, 0.6, 1.0, 1.4 on targets 2, 4, 10, 10: relative 10, 15, 10, 14 %.
  const std::vector<double> target = {2, 4, 10, 10};
  const std::vector<double> predicted = {2.2, 3.4, 11.0, 8.6};
  const ErrorFigures f = error_figures(predicted, target);
  EXPECT_EQ(f.samples, 4u);
  EXPECT_NEAR(f.max_abs, 1.4, kTol);
  EXPECT_NEAR(f.mean_abs, (0.2 + 0.6 + 1.0 + 1.4) / 4, kTol);
  EXPECT_DOUBLE_EQ(f.share_abs_below(1.0), 50.0);  // 0.2, 0.6; 1.0 is not below 1
  EXPECT_DOUBLE_EQ(f.share_abs_below(1.5), 100.0);
  EXPECT_DOUBLE_EQ(f.share_rel_below(10.0 + 1e-9), 50.0);
  EXPECT_DOUBLE_EQ(f.share_rel_below(20.0), 100.0);
  const ErrorFigures empty = error_figures({}, {});
  EXPECT_EQ(empty.samples, 0u);
  EXPECT_TRUE(std::isnan(empty.max_abs));
  EXPECT_TRUE(std::isnan(empty.share_abs_below(1.0)));
}

}  // namespace
}  // namespace cnclab
