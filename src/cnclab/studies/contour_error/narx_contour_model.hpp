#pragma once
// The contour predictor of a trained seed-002 narx result
// (experiments/contour_error/narx.yaml): its two networks, their
// normalisation (the following_error generator's mapminmax ranges, recovered
// from the dataset it trained on) and that dataset's tool path, limits and
// machine, so a downstream job plans on the machine the predictor knows.
#include <filesystem>
#include <memory>
#include <ostream>

#include "cnclab/data/following_error.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/studies/contour_error/contour_predictor.hpp"

namespace cnclab {

// One network of the record per axis (x, y) with its physical ranges:
// input v [mm/s] in ranges.velocity, output e [mm] in
// ranges.following_error / 1000 (the dataset stores µm); further input
// channels (direction_x, ...: the generator's extra_inputs, already in
// [-1, 1]) computed with `direction` (the dataset's options, its period the
// controller period). cnclab::Error naming the result when it is not a
// complete narx result with networks x and y, or a channel is not one of
// v_<axis>, then sign/direction/reversal_<axis>.
ContourPredictor contour_predictor_from(const RunRecord& narx_result,
                                        const FollowingErrorRanges& ranges,
                                        const AxisDirectionOptions& direction,
                                        const std::string& result_file);

struct TrainedContourModel {
  UpstreamResult upstream;        // the narx result and its experiment
  FollowingErrorOptions dataset;  // its dataset's options (path, limits, machine)
  FollowingErrorRanges ranges;
  std::unique_ptr<NurbsPlanarPath> path;  // the dataset's random NURBS path, redrawn
  double contour_rms = 0.0;  // the predictor's closed-loop contour RMS on validation [mm]
  // The dataset's direction feature options with the controller period.
  AxisDirectionOptions direction() const;
  // Its predictor (contour_predictor_from).
  ContourPredictor predictor() const;
};

// Loads the upstream narx result (load_upstream: MissingResults naming the
// command when it has not run), obtains its dataset from the cache in
// `data_dir` (generating it if absent) for the ranges, and redraws the path
// from the generator seed (the generator draws the path first). ConfigError
// when the upstream is not a following_error narx experiment. `dataset`
// (optional) receives the dataset itself.
TrainedContourModel load_trained_contour_model(const std::filesystem::path& narx_experiment,
                                               const std::filesystem::path& results_dir,
                                               const std::filesystem::path& data_dir,
                                               const std::string& profile, std::ostream* log,
                                               Dataset* dataset = nullptr);

}  // namespace cnclab
