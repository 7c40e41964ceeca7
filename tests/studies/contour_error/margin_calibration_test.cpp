// The margin calibration (margin_calibration.hpp) with a predictor that
// predicts no error at all: its residual is then the simulated contour error
// itself, so every margin and summary is a statistic of the dataset's
// contour_exact column, computed here by sorting (the calibration uses
// nth_element), per feed band of the validation ticks.
#include "cnclab/studies/contour_error/margin_calibration.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "studies/contour_error/margin_fixtures.hpp"

namespace cnclab {
namespace {

using testing::plans;
using testing::zero_model;

// The ceil(q n)-th smallest, by sorting.
double sorted_quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(v.size()) - 1e-9));
  return v[std::max<std::size_t>(k, 1) - 1];
}

TEST(MarginCalibration, EmpiricalQuantileIsTypeOne) {
  std::vector<double> v = {7, 3, 10, 1, 9, 2, 8, 4, 6, 5};
  EXPECT_EQ(empirical_quantile(v, 0.9), 9.0);  // R: quantile(1:10, 0.9, type = 1)
  EXPECT_EQ(empirical_quantile(v, 0.91), 10.0);
  EXPECT_EQ(empirical_quantile(v, 0.05), 1.0);
  EXPECT_EQ(empirical_quantile(v, 0.5), 5.0);
  std::vector<double> none;
  EXPECT_TRUE(std::isnan(empirical_quantile(none, 0.5)));
}

// Two bands (150 mm/s), the 0.95 quantile, no pooling.
MarginCalibrationOptions two_band_options() {
  MarginCalibrationOptions o;
  o.quantile = 0.95;
  o.feed_bands = {150};
  o.min_ticks = 1;
  return o;
}

TEST(MarginCalibration, ZeroPredictorGivesTheQuantilesOfTheSimulatedError) {
  const Dataset& d = plans();
  ContourPredictor zero(zero_model(), zero_model());
  MarginCalibrationOptions o = two_band_options();
  const MarginCalibration c = calibrate_margins(zero, d, o);
  std::vector<std::vector<double>> band(2);
  std::vector<double> all, slowed;
  const auto row = [&](const char* name) { return d.metadata_row(name); };
  for (Eigen::Index k = 0; k < d.metadata.cols(); ++k) {
    if (d.metadata(row("validation"), k) != 1.0) continue;
    const double exact = d.metadata(row("contour_exact"), k) * 1e-3;
    const double speed = std::hypot(d.metadata(row("v_ref_x"), k), d.metadata(row("v_ref_y"), k));
    band[speed < 150 ? 0 : 1].push_back(exact);
    all.push_back(exact);
    if (d.metadata(row("feed_factor"), k) < 1.0) slowed.push_back(exact);
  }
  ASSERT_EQ(c.band_ticks, (std::vector<std::size_t>{band[0].size(), band[1].size()}));
  ASSERT_GT(band[0].size(), 0u);
  ASSERT_GT(band[1].size(), 0u);
  EXPECT_EQ(c.margins.margin[0], sorted_quantile(band[0], 0.95));
  EXPECT_EQ(c.margins.margin[1], sorted_quantile(band[1], 0.95));
  EXPECT_EQ(c.validation.ticks, all.size());
  EXPECT_EQ(c.slowed.ticks, slowed.size());
  EXPECT_EQ(c.slowed.ticks, 1200u);  // the second half of the 2400-tick run at 0.5
  EXPECT_EQ(c.slowed.underprediction_p99, sorted_quantile(slowed, 0.99));
  EXPECT_EQ(c.slowed.underprediction_max, *std::max_element(slowed.begin(), slowed.end()));
  double sq = 0;
  for (const double x : slowed) sq += x * x;
  EXPECT_NEAR(c.slowed.rms, std::sqrt(sq / static_cast<double>(slowed.size())), 1e-15);
  EXPECT_TRUE(std::isnan(c.slowed.correlation));  // a constant prediction

  // A band with fewer ticks than min_ticks takes the quantile of all ticks.
  o.min_ticks = std::max(band[0].size(), band[1].size()) + 1;
  const MarginCalibration pooled = calibrate_margins(zero, d, o);
  EXPECT_EQ(pooled.margins.margin[0], sorted_quantile(all, 0.95));
  EXPECT_EQ(pooled.margins.margin[1], sorted_quantile(all, 0.95));
}

// With a reversal window the validation ticks split in two classes: at
// most the window after either axis's commanded velocity changed sign
// outside the deadband (0 -> +-1 at a start included), counted here by hand
// over each run's pieces in dataset order, and the others; each class has
// its own quantile per band. Window 0 gives the one-class margins.
TEST(MarginCalibration, ReversalWindowGivesTheTicksAfterAChangeOfDirectionTheirOwnMargins) {
  const Dataset& d = plans();
  ContourPredictor zero(zero_model(), zero_model());
  MarginCalibrationOptions o = two_band_options();
  const MarginCalibration one = calibrate_margins(zero, d, o);
  o.reversal_window = 0.03;
  const MarginCalibration c = calibrate_margins(zero, d, o);
  const auto row = [&](const char* name) { return d.metadata_row(name); };
  std::vector<double> steady[2], after[2];
  double run = NAN, piece = NAN;
  double direction[2] = {0, 0}, since[2] = {INFINITY, INFINITY};
  // The dataset holds each run's first half, then every run's second half:
  // a run's ticks in time order are its rows of one feed factor.
  for (const double factor : {0.5, 1.0}) {
    for (Eigen::Index k = 0; k < d.metadata.cols(); ++k) {
      if (d.metadata(row("feed_factor"), k) != factor) continue;
      if (factor != run || d.metadata(row("piece"), k) != piece) {
        direction[0] = direction[1] = 0;
        since[0] = since[1] = INFINITY;
      }
      run = factor;
      piece = d.metadata(row("piece"), k);
      for (int a = 0; a < 2; ++a) {
        const double v = d.metadata(row(a == 0 ? "v_ref_x" : "v_ref_y"), k);
        const double sign = std::abs(v) > 1e-3 ? (v > 0 ? 1.0 : -1.0) : 0.0;
        if (sign != 0 && sign != direction[a]) {
          direction[a] = sign;
          since[a] = 0;
        } else {
          since[a] += 1e-3;
        }
      }
      if (d.metadata(row("validation"), k) != 1.0) continue;
      const double exact = d.metadata(row("contour_exact"), k) * 1e-3;
      const double speed = std::hypot(d.metadata(row("v_ref_x"), k), d.metadata(row("v_ref_y"), k));
      (std::min(since[0], since[1]) <= 0.03 + 1e-6 ? after : steady)[speed < 150 ? 0 : 1].push_back(
          exact);
    }
  }
  ASSERT_GT(after[0].size() + after[1].size(), 0u);
  ASSERT_GT(steady[0].size() + steady[1].size(), 0u);
  EXPECT_EQ(c.band_ticks, (std::vector<std::size_t>{steady[0].size(), steady[1].size()}));
  EXPECT_EQ(c.after_reversal_band_ticks,
            (std::vector<std::size_t>{after[0].size(), after[1].size()}));
  EXPECT_EQ(c.margins.reversal_window, 0.03);
  for (std::size_t b = 0; b < 2; ++b) {
    if (!steady[b].empty()) {
      EXPECT_EQ(c.margins.margin[b], sorted_quantile(steady[b], 0.95)) << b;
    }
    if (!after[b].empty()) {
      EXPECT_EQ(c.margins.after_reversal[b], sorted_quantile(after[b], 0.95)) << b;
    }
  }
  // The residual summaries do not depend on the classes; window 0 is one class.
  EXPECT_EQ(c.validation.underprediction_p99, one.validation.underprediction_p99);
  EXPECT_TRUE(one.margins.after_reversal.empty());
  EXPECT_TRUE(one.after_reversal_band_ticks.empty());
  EXPECT_EQ(one.margins.reversal_window, 0.0);
  EXPECT_NO_THROW(c.margins.validate());

  // A band of a class with fewer than min_ticks takes the quantile of its
  // class, or of all ticks when the class has fewer too.
  std::vector<double> all_after = after[0], all;
  all_after.insert(all_after.end(), after[1].begin(), after[1].end());
  for (const auto* v : {&steady[0], &steady[1], &after[0], &after[1]}) {
    all.insert(all.end(), v->begin(), v->end());
  }
  o.min_ticks = std::max(after[0].size(), after[1].size()) + 1;
  const double expected = all_after.size() >= o.min_ticks ? sorted_quantile(all_after, 0.95)
                                                          : sorted_quantile(all, 0.95);
  const MarginCalibration pooled = calibrate_margins(zero, d, o);
  EXPECT_EQ(pooled.margins.after_reversal[0], expected);
  EXPECT_EQ(pooled.margins.after_reversal[1], expected);
}

TEST(MarginCalibration, BadOptionsAndPlansAreNamed) {
  MarginCalibrationOptions o;
  o.feed_bands = {100, 50};
  try {
    o.validate();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "feed_bands");
  }
  o = {};
  o.reversal_window = -0.01;
  try {
    o.validate();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "reversal_window");
  }
  ContourPredictor zero(zero_model(), zero_model());
  Dataset no_columns = plans();
  no_columns.metadata_names[no_columns.metadata_row("contour_exact")] = "something_else";
  EXPECT_NE(testing::error_message<Error>([&] {
              calibrate_margins(zero, no_columns, {});
            }).find("no metadata column contour_exact"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab
