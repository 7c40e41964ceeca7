#pragma once
// The feedrate loop's prediction margin from data the predictor never saw
// (docs/motion.md, "Calibrated margins"): the contour predictor runs over
// the plans of a following_error dataset (each run of the path from rest, as
// the loop runs it over a plan: from rest at each piece the generator
// planned and simulated from rest) and its residual r = simulated - predicted
// contour error is collected on the validation ticks (the second halves:
// path the predictor was not trained on). Per feed band (the tick's path
// speed |v|), the margin is the `quantile` of r: a plan whose predicted
// error stays within eps_max - margin(|v|) at every tick then exceeds eps_max
// at a tick only where r > margin, on at most 1 - quantile of the ticks if
// the plan's residuals are distributed as the calibration's (a split-
// conformal bound, per band). quantile = the required share (0.999) makes
// that bound the verification's criterion. With a reversal_window, the ticks
// within it after either axis's commanded direction changed (a reversal or
// the start from rest, AxisDirection::since_change) are a class of their
// own with their own margins per band: the predictor's largest misses are
// the stick-slip spikes there, and one quantile over all ticks charges
// their margin to every tick (docs/motion.md, "Calibrated
// margins").
#include <cstddef>
#include <string>
#include <vector>

#include "cnclab/data/dataset.hpp"
#include "cnclab/studies/contour_error/contour_predictor.hpp"
#include "cnclab/studies/contour_error/feedrate_optimisation.hpp"

namespace cnclab {

struct MarginCalibrationOptions {
  double quantile = 0.999;  // of r per band, in (0, 1)
  // Band edges [mm/s], ascending, > 0: bands [0, e0), [e0, e1), ..., [e_last, inf).
  std::vector<double> feed_bands = {50, 100, 150, 200};
  // A band with fewer validation ticks takes the quantile of all ticks of
  // its class (of all ticks when the class has fewer too).
  std::size_t min_ticks = 1000;
  // [s], >= 0: ticks at most this long after a change of direction form the
  // after-reversal class (0: one class). The stick-slip transient lasts a
  // few servo time constants (1/Kp = 25 ms on the router).
  double reversal_window = 0.0;

  void validate() const;  // OptionError naming the field
};

struct ResidualSummary {
  std::size_t ticks = 0;
  double rms = 0.0;                  // of r [mm]
  double underprediction_p99 = 0.0;  // 99th percentile of r [mm]
  double underprediction_max = 0.0;  // max r [mm]
  double correlation = 0.0;          // Pearson, predicted vs simulated
};

struct MarginCalibration {
  FeedBandMargins margins;
  std::vector<std::size_t> band_ticks;  // validation ticks per band (outside the reversal window)
  std::vector<std::size_t> after_reversal_band_ticks = {};  // within it (empty: no window)
  ResidualSummary validation;                               // every validation tick
  ResidualSummary slowed;  // those of runs with feed_factor < 1 (ticks 0: none)
};

// Runs `predictor` over every run of `plans` (a following_error dataset:
// metadata v_ref_*, ref_*, d1_*, d2_*, contour_exact, validation and, with
// feed factors, feed_factor and piece), from rest at every piece, and
// calibrates as above. cnclab::Error when a column is missing or there is
// no validation tick.
MarginCalibration calibrate_margins(ContourPredictor& predictor, const Dataset& plans,
                                    const MarginCalibrationOptions& options);

// The empirical q-quantile of `values` (the ceil(q n)-th smallest; type 1 of
// Hyndman and Fan 1996, R's quantile(type = 1)). `values` is reordered.
double empirical_quantile(std::vector<double>& values, double q);

}  // namespace cnclab
