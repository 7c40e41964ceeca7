#pragma once
// Seed 002's data recipe (Sec. II) on the simulated machine: a random NURBS
// tool path (nurbs_path.hpp), its jerk-limited minimum-time feedrate
// (motion/feedrate_planner.hpp, Ipopt), the 1 ms interpolator, the simulated
// biaxial feed drives run `runs` times (repeatability: each run draws its
// scale noise from its own stream), the runs averaged, the averaged following
// errors smoothed with the csaps-equivalent spline (p on the sample index,
// motion/smoothing_spline.hpp), inputs and targets normalised to [-1, 1]
// (MATLAB mapminmax over the whole run, as the paper normalises before
// dividing the set), the first half for training, the second for validation.
//
// Columns (N samples at the controller period):
//   inputs  (2, "1"):  v_x, v_y  reference axis velocity, mapminmax to [-1, 1]
//   targets (2, "1"):  e_x, e_y  smoothed mean following error, mapminmax to [-1, 1]
//   metadata (not inputs; physical units):
//     time [s], u (path parameter), ref_x, ref_y [mm] reference position,
//     actual_x, actual_y [mm] = ref - e (the "actual position" of the logged
//     following error), v_ref_x, v_ref_y [mm/s], e_ref_x, e_ref_y [µm]
//     following error (mean of the runs, smoothed), d1_x, d1_y, d2_x, d2_y
//     (C'(u), C''(u): the interpolator's geometry the Taylor estimate needs),
//     contour_exact, contour_taylor, contour_tangent, contour_osculating [µm]
//     (motion/contour_error.hpp; Taylor as |eps_c|), validation (0 first
//     half, 1 second half).
//
// Planning data (docs/motion.md, "A predictor for planning"): with
// `feed_factors` the generator also runs time-scaled copies of the plan
// (u(f t): every axis velocity x f, acceleration x f^2, jerk x f^3), each
// for the same part of the path, and splits each at its time midpoint (the
// same path point for every factor): the dataset holds the first halves of
// every run in factor order, then their second halves, so the first N / 2
// samples train and the rest validate as in seed 002's split. Three more
// metadata columns then: feed_factor (f), sequence (a new id at every half
// and every piece: independent series, experiment/narx_runner.cpp starts
// each from its measured states) and piece (a new id at every cold start). `extra_inputs` adds
// direction features of the commanded velocities as inputs (motion/axis_direction.hpp; in [-1, 1],
// not normalised). `plan_length` plans the path in consecutive pieces from
// rest to rest instead of in one, each simulated from the machine's initial
// state with its features from rest (cold starts: the sections the feedrate
// job plans, checks and predicts, following_error_runs.hpp). Single unsmoothed runs: runs 1,
// smoothing 1 (the interpolating spline: the run itself). With the new options off the dataset and
// its identity are seed 002's as before. The normalisation ranges are stored with the data they
// were fitted on: they are exactly [min, max] of the physical columns v_ref_* and e_ref_*,
// recovered by following_error_ranges() (no separate copy to disagree).
#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/data/dataset.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/data/nurbs_path.hpp"
#include "cnclab/motion/axis_direction.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/machine.hpp"

namespace cnclab {

struct FollowingErrorOptions {
  // The random tool path. Default 1450 control points: a walk of ~58 m, which
  // the planner turns into > 172 s at seed 002's limits.
  RandomNurbsPathOptions path = [] {
    RandomNurbsPathOptions o;
    o.control_points = 1450;
    return o;
  }();
  FeedratePlannerOptions planner;  // limits: seed 002's 300 mm/s, 2000 mm/s^2, 50000 mm/s^3
  MachineOptions machine;          // configs/machines/biaxial_router.yaml
  std::size_t runs = 10;           // seed 002: "repeated 10 times", >= 1
  double smoothing = 5e-2;         // csaps p (seed 002), on the sample index; in [0, 1]
  // Samples kept from the start of the run (seed 002: "over 170000"); the
  // run must be at least this long. 0 = the whole run. >= 8 otherwise.
  std::size_t samples = 172'000;
  // Feed factors in (0, 1], each once; empty: seed 002's single run (above).
  std::vector<double> feed_factors;
  // Direction features as extra inputs: "sign", "direction", "reversal".
  std::vector<std::string> extra_inputs;
  AxisDirectionOptions direction;  // its period is the machine's controller period
  // The plan in consecutive pieces of about this arc length [mm], each from
  // rest to rest (the machine stops at every joint, as a feedrate plan of a
  // section does); 0: the whole path in one plan (seed 002).
  double plan_length = 0.0;

  void validate() const;  // OptionError naming the field
};

// Per-column mapminmax: physical [min, max] -> [-1, 1].
struct ColumnRange {
  double min = 0.0, max = 0.0;
};
struct FollowingErrorRanges {
  std::array<ColumnRange, 2> velocity;         // v_ref_x, v_ref_y [mm/s]
  std::array<ColumnRange, 2> following_error;  // e_ref_x, e_ref_y [µm]
};

// y = -1 + 2 (x - min) / (max - min): exactly -1 at min and 1 at max.
// Throws cnclab::Error naming `what` and the sample for a non-finite value,
// or when max == min (a constant column cannot be normalised).
Eigen::VectorXd normalise_minmax(const Eigen::VectorXd& x, const std::string& what,
                                 ColumnRange* range = nullptr);

// physical = min + (y + 1) (max - min) / 2, the inverse of normalise_minmax.
inline double to_physical(double y, const ColumnRange& r) {
  return r.min + (y + 1.0) * 0.5 * (r.max - r.min);
}

// `progress` (optional) hears of the planning windows, the simulated runs
// and the contour errors.
Dataset generate_following_error_dataset(const FollowingErrorOptions& options, Rng& rng,
                                         const ProgressCallback& progress = {});

// The ranges of a following_error dataset's normalisation, from its metadata;
// cnclab::Error if a column is missing.
FollowingErrorRanges following_error_ranges(const Dataset& dataset);

// Index of the first validation sample (the second half: N / 2).
std::size_t first_validation_sample(const Dataset& dataset);

// The registered generator `following_error`. Options (dataset.options):
//   path: {degree, control_points, x_min, x_max, y_min, y_max, step_min,
//          step_max, max_turn, weight_min, weight_max, min_curvature_radius}
//   limits: {velocity, acceleration, jerk}     # both axes
//   grid_spacing: 1                            # planner grid [mm]
//   machine: configs/machines/biaxial_router.yaml   # a file or the map inline
//   runs: 10
//   smoothing: 0.05
//   samples: 172000
//   feed_factors: [1, 0.7, 0.5]                # optional: planning data (above)
//   extra_inputs: [direction, reversal]        # optional
//   direction: {deadband: 0.001, reversal_time_constant: 0.02}
//   plan_length: 150                           # optional: pieces from rest [mm]
class FollowingErrorGenerator : public DatasetGenerator {
 public:
  explicit FollowingErrorGenerator(FollowingErrorOptions options);  // validates
  std::string name() const override { return "following_error"; }
  // 2: the planner's limit refinement (docs/motion.md) changes the reference, so
  // datasets cached by version 1 are regenerated. 3: the Taylor estimate's
  // denominator sign (motion/contour_error.hpp) changes contour_taylor.
  int version() const override { return 3; }
  DatasetShape shape() const override;
  std::string options_yaml() const override;
  Dataset generate(Rng& rng, const ProgressCallback& progress) const override {
    return generate_following_error_dataset(options_, rng, progress);
  }
  Dataset generate(Rng& rng) const override {
    return generate_following_error_dataset(options_, rng);
  }
  const FollowingErrorOptions& options() const { return options_; }

 private:
  FollowingErrorOptions options_;
};

// dataset.options of `following_error`: {path, limits, grid_spacing, machine, runs,
// smoothing, samples, feed_factors, extra_inputs, direction}.
const FieldList<FollowingErrorOptions>& following_error_fields();

std::shared_ptr<const DatasetGenerator> read_following_error(const ConfigReader& options);

}  // namespace cnclab
