// The margins stored with a predictor's result (stored_margins.hpp): a
// round trip of every field, a file that is not complete is named, and
// predictor_margins takes what is stored for the same result and options
// (values no calibration of the zero predictor gives) but calibrates again,
// equal to calibrate_margins itself, for another training or other options.
#include "cnclab/studies/contour_error/stored_margins.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"
#include "studies/contour_error/margin_fixtures.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

StoredMargins crafted_margins() {
  StoredMargins m;
  m.predictor_result = "results/narx/narx-0123.h5";
  m.predictor_identity = "identity-a";
  m.dataset_hash = "abc123";
  m.options.quantile = 0.99;
  m.options.feed_bands = {150};
  m.options.min_ticks = 1;
  m.calibration.margins = {{150}, {0.0042, 0.0071}};
  m.calibration.band_ticks = {1000, 1400};
  m.calibration.validation = {2400, 0.003, 0.006, 0.009, 0.75};
  m.calibration.slowed = {1200, 0.002, 0.004, 0.005, 0.5};
  m.provenance = make_provenance(0);
  finish_provenance(m.provenance);
  return m;
}

void expect_same_residuals(const ResidualSummary& a, const ResidualSummary& b) {
  EXPECT_EQ(a.ticks, b.ticks);
  EXPECT_EQ(a.rms, b.rms);
  EXPECT_EQ(a.underprediction_p99, b.underprediction_p99);
  EXPECT_EQ(a.underprediction_max, b.underprediction_max);
  EXPECT_EQ(a.correlation, b.correlation);
}

TEST(StoredMargins, RoundTripKeepsEveryField) {
  testing::TempDir dir;
  const StoredMargins m = crafted_margins();
  const fs::path file = stored_margins_path(dir.path() / "narx-0123.h5");
  EXPECT_EQ(file, dir.path() / "narx-0123-margins.h5");
  EXPECT_FALSE(read_stored_margins(file).has_value());
  write_stored_margins(file, m);
  const std::optional<StoredMargins> r = read_stored_margins(file);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->predictor_result, m.predictor_result);
  EXPECT_EQ(r->predictor_identity, m.predictor_identity);
  EXPECT_EQ(r->dataset_hash, m.dataset_hash);
  EXPECT_EQ(r->options.quantile, m.options.quantile);
  EXPECT_EQ(r->options.feed_bands, m.options.feed_bands);
  EXPECT_EQ(r->options.min_ticks, m.options.min_ticks);
  EXPECT_EQ(r->calibration.margins.edges, m.calibration.margins.edges);
  EXPECT_EQ(r->calibration.margins.margin, m.calibration.margins.margin);
  EXPECT_EQ(r->calibration.band_ticks, m.calibration.band_ticks);
  expect_same_residuals(r->calibration.validation, m.calibration.validation);
  expect_same_residuals(r->calibration.slowed, m.calibration.slowed);
  EXPECT_EQ(r->provenance.start_utc, m.provenance.start_utc);
  EXPECT_EQ(r->provenance.git_commit, m.provenance.git_commit);
  EXPECT_EQ(r->options.reversal_window, 0.0);
  EXPECT_TRUE(r->calibration.margins.after_reversal.empty());

  // With margins after a change of direction.
  StoredMargins w = m;
  w.options.reversal_window = w.calibration.margins.reversal_window = 0.05;
  w.calibration.margins.after_reversal = {0.0093, 0.0121};
  w.calibration.after_reversal_band_ticks = {310, 95};
  write_stored_margins(file, w);
  const std::optional<StoredMargins> rw = read_stored_margins(file);
  ASSERT_TRUE(rw.has_value());
  EXPECT_EQ(rw->options.reversal_window, 0.05);
  EXPECT_EQ(rw->calibration.margins.reversal_window, 0.05);
  EXPECT_EQ(rw->calibration.margins.after_reversal, w.calibration.margins.after_reversal);
  EXPECT_EQ(rw->calibration.after_reversal_band_ticks, w.calibration.after_reversal_band_ticks);
  EXPECT_EQ(rw->calibration.margins.margin, m.calibration.margins.margin);
}

TEST(StoredMargins, AFileThatIsNotCompleteIsNamed) {
  testing::TempDir dir;
  const fs::path file = dir.path() / "narx-margins.h5";
  std::ofstream(file) << "not hdf5";
  const std::string message = testing::error_message<Error>([&] { read_stored_margins(file); });
  EXPECT_NE(message.find(file.string()), std::string::npos) << message;
  StoredMargins bad = crafted_margins();
  bad.calibration.band_ticks.pop_back();
  EXPECT_NE(testing::error_message<Error>([&] {
              write_stored_margins(dir.path() / "bad-margins.h5", bad);
            }).find("do not fit together"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir.path() / "bad-margins.h5"));
  bad = crafted_margins();
  bad.options.reversal_window = 0.05;  // the options' window, but no margins for it
  EXPECT_NE(testing::error_message<Error>([&] {
              write_stored_margins(dir.path() / "bad-margins.h5", bad);
            }).find("do not fit together"),
            std::string::npos);
  bad = crafted_margins();
  bad.calibration.margins.after_reversal = {0.01, 0.02};  // without their tick counts
  EXPECT_NE(testing::error_message<Error>([&] {
              write_stored_margins(dir.path() / "bad-margins.h5", bad);
            }).find("do not fit together"),
            std::string::npos);
}

TEST(StoredMargins, TheStoredOnesAreUsedForTheSameResultAndOptionsOnly) {
  testing::TempDir dir;
  const Dataset& d = testing::plans();
  ContourPredictor zero(testing::zero_model(), testing::zero_model());
  const fs::path result = dir.path() / "narx-0123.h5";
  StoredMargins stored = crafted_margins();
  stored.predictor_result = result;
  write_stored_margins(stored_margins_path(result), stored);

  std::ostringstream note;
  const StoredMargins same =
      predictor_margins(zero, d, "abc123", result, "identity-a", stored.options, note);
  EXPECT_EQ(same.calibration.margins.margin, stored.calibration.margins.margin);
  EXPECT_NE(note.str().find("margins stored with the predictor: "), std::string::npos);
  EXPECT_EQ(note.str().find("calibrating"), std::string::npos) << note.str();

  // Another training of the same config: calibrated again and stored.
  const MarginCalibration direct = calibrate_margins(zero, d, stored.options);
  std::ostringstream retrained;
  const StoredMargins again =
      predictor_margins(zero, d, "abc123", result, "identity-b", stored.options, retrained);
  EXPECT_EQ(again.calibration.margins.margin, direct.margins.margin);
  EXPECT_NE(again.calibration.margins.margin, stored.calibration.margins.margin);
  EXPECT_NE(retrained.str().find("an earlier training; calibrating again"), std::string::npos)
      << retrained.str();
  EXPECT_EQ(read_stored_margins(stored_margins_path(result))->predictor_identity, "identity-b");

  // Other options: calibrated again.
  MarginCalibrationOptions other = stored.options;
  other.quantile = 0.9;
  std::ostringstream options_note;
  const StoredMargins third =
      predictor_margins(zero, d, "abc123", result, "identity-b", other, options_note);
  EXPECT_EQ(third.calibration.margins.margin, calibrate_margins(zero, d, other).margins.margin);
  EXPECT_NE(options_note.str().find("other calibration options"), std::string::npos);

  // Another reversal window is other options too.
  MarginCalibrationOptions window = other;
  window.reversal_window = 0.03;
  std::ostringstream window_note;
  const StoredMargins fourth =
      predictor_margins(zero, d, "abc123", result, "identity-b", window, window_note);
  EXPECT_NE(window_note.str().find("other calibration options"), std::string::npos);
  EXPECT_EQ(fourth.calibration.margins.after_reversal,
            calibrate_margins(zero, d, window).margins.after_reversal);
  EXPECT_FALSE(fourth.calibration.margins.after_reversal.empty());
}

}  // namespace
}  // namespace cnclab
