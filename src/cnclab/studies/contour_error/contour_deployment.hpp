#pragma once
// Seed 002's part of `cnclab predict` and `cnclab export`
// (deploy/sequence_extension.hpp) for narx networks trained on the
// following_error dataset:
// - physical columns: network x reads v_ref_x [mm/s] and predicts e_ref_x
//   [µm] (likewise y), through the dataset's mapminmax over the training
//   run's ranges (data/following_error.hpp);
// - per tick, with networks x and y and the interpolator's geometry (the
//   dataset's ref_x, ref_y, d1_*, d2_* [mm], or a CSV's columns of those
//   names): contour_error.<label> [µm], the magnitude of the Taylor estimate
//   (Eqs. 3-6, motion/contour_error.hpp) at the tool position P = R - e of
//   the predicted (or measured) following errors e, as the contour_rms
//   metric computes it (narx_metrics.hpp); contour_error.measured is the
//   dataset's exact contour error (contour_exact), the truth the estimates
//   are scored against;
// - exports: NAME_contour_error in C (and contour_error in torch), the same
//   estimate from NAME_step's out[] (the real-time contour predictor of Sec.
//   III, Fig. 12, for a controller).
namespace cnclab {

// Registers the extension (from register_contour_error_study()).
void register_contour_deployment();

}  // namespace cnclab
