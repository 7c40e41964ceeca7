#pragma once
// Seed 002's trial metrics of a narx experiment on a following_error dataset
// (experiment/sequence_metrics.hpp), in µm. Per axis (x, y):
//   closed_loop_rms_<axis>, closed_loop_max_<axis>  the closed-loop prediction
//       error over the validation part (steps from first_step; NaN if unstable)
//   zero_rms_<axis>, zero_max_<axis>  the same for predicting e = 0
// Over both axes:
//   stable       1 when every network's closed loop stayed finite and within
//                kStableBound (dataset units, i.e. 10x the [-1, 1] range), else 0
//   contour_rms, contour_max  Taylor contour error (Eqs. 3-6) from the predicted
//                following errors against the exact one (NaN unless stable with x and y)
//   exact_contour_mean, exact_contour_max  the exact contour error itself
//   <estimate>_mean_abs_diff, <estimate>_max_abs_diff  |estimate - exact| for the
//                contour estimates taylor, tangent, osculating (motion/contour_error.hpp)
// The dataset-level numbers (zero_*, exact_*, estimates) do not depend on the
// network; every trial carries them so a table needs no second source. All
// numbers cover the same steps: the validation part from first_step (the
// first predicted step, after the delays' measured initial states), so the
// zero predictor is scored where the network is. Stored as
// validation.<name> (experiment/spec.hpp: a narx run's one split).
namespace cnclab {

inline constexpr double kStableBound = 10.0;

// Registers the group (from register_contour_error_study()).
void register_contour_error_metrics();

}  // namespace cnclab
