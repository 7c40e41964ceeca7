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

TEST(MarginCalibration, ZeroPredictorGivesTheQuantilesOfTheSimulatedError) {
  const Dataset& d = plans();
  ContourPredictor zero(zero_model(), zero_model());
  MarginCalibrationOptions o;
  o.quantile = 0.95;
  o.feed_bands = {150};
  o.min_ticks = 1;
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

TEST(MarginCalibration, BadOptionsAndPlansAreNamed) {
  MarginCalibrationOptions o;
  o.feed_bands = {100, 50};
  try {
    o.validate();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "feed_bands");
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
