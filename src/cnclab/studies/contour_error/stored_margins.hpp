#pragma once
// The calibrated margins kept with the predictor's result (docs/motion.md,
// "Calibrated margins"): a margin calibration (margin_calibration.hpp) is a
// property of one trained predictor, so it is stored beside that predictor's
// result, as <result stem>-margins.h5, and every feedrate job that plans with
// the predictor reads it from there: the loop's promise rests on the
// predictor's validation plans, whatever path the job then plans on.
//
// File layout (HDF5, format cnclab-margins version 1, complete marker):
//   predictor_result    string   the predictor's result file, as found
//   predictor_identity  string   result_identity() of that result
//   dataset_hash        string   content hash of the plans' dataset
//   split               string   "validation" (the only ticks scored)
//   quantile, min_ticks double / int   MarginCalibrationOptions
//   feed_bands          float64[] band edges [mm/s]
//   margins             float64[] per band [mm]
//   band_ticks          int64[]   validation ticks per band
//   reversal_window     double    [s]; 0 (or absent: files before it) one class
//   after_reversal_margins, after_reversal_band_ticks   as margins and
//                       band_ticks, within the window (only when it is > 0)
//   validation/, slowed/   ticks, rms, underprediction_p99,
//                          underprediction_max [mm], correlation
//   provenance/         who calibrated, when (io/provenance.hpp)
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

#include "cnclab/io/provenance.hpp"
#include "cnclab/studies/contour_error/margin_calibration.hpp"

namespace cnclab {

struct StoredMargins {
  std::filesystem::path predictor_result;  // the predictor's result file
  std::string predictor_identity;          // result_identity() of it
  std::string dataset_hash;                // the plans the residuals came from
  MarginCalibrationOptions options;
  MarginCalibration calibration;
  Provenance provenance;
};

// <dir>/<stem>-margins.h5 beside `predictor_result`.
std::filesystem::path stored_margins_path(const std::filesystem::path& predictor_result);

// Writes atomically (nothing half-written on failure).
void write_stored_margins(const std::filesystem::path& file, const StoredMargins& margins);
// std::nullopt when `file` does not exist; cnclab::Error naming the file
// and the entry when it is not a complete cnclab-margins file.
std::optional<StoredMargins> read_stored_margins(const std::filesystem::path& file);

// The predictor's margins for `options`: the stored ones when they are of
// this very result (identity) and these options; otherwise (a result
// trained before margins were stored, or stored for other options or an
// earlier training of the same config) the calibration runs now over the
// validation ticks of `plans` and is stored beside the result for the next
// job. `note` hears which (and why a stored file was not used). `predictor`
// is reset by a calibration.
StoredMargins predictor_margins(ContourPredictor& predictor, const Dataset& plans,
                                const std::string& dataset_hash,
                                const std::filesystem::path& predictor_result,
                                const std::string& predictor_identity,
                                const MarginCalibrationOptions& options, std::ostream& note);

}  // namespace cnclab
