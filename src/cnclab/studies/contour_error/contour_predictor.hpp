#pragma once
// The neural contour error predictor of seed 002 (Sec. III, Fig. 12): the two
// per-axis NARX networks predict the following errors from the reference
// velocities, and the Taylor estimate (Eqs. 3-6, taylor_contour_error)
// turns them and the interpolator's local path geometry into the predicted
// contour error, once per 1 ms tick. It lives in experiment, the first
// module that sees both nn and motion (docs/architecture.md's arrows).
//
// Real-time contract as NarxPredictor: construction may allocate and throw;
// reset() and step() never allocate and never throw. step() checks all its
// inputs first; on bad input it returns the status and changes nothing
// (neither the networks' state nor `out`), so the caller decides whether to
// skip the tick or reset.
#include <array>
#include <vector>

#include "cnclab/motion/axis_direction.hpp"
#include "cnclab/motion/planar_path.hpp"
#include "cnclab/nn/narx_predictor.hpp"

namespace cnclab {

struct ContourPrediction {
  Vec2 following_error = Vec2::Zero();  // predicted e = R - P per axis [mm]
  Vec2 actual = Vec2::Zero();           // predicted tool position P = R - e [mm]
  // taylor_contour_error(reference, actual): the signed eps_c of Eq. 3 (its
  // magnitude is the contour error estimate) [mm].
  double contour_error = 0.0;
};

class ContourPredictor {
 public:
  // One trained network per axis (x, y). Throws as NarxPredictor. A network
  // with more input channels than the velocity takes the direction features
  // `extra` of its axis's velocity, in that order (the following_error
  // generator's extra_inputs, computed here with the same class and
  // options): cnclab::Error when a network's channel count is not
  // 1 + extra.size().
  ContourPredictor(NarxAxisModel x, NarxAxisModel y, const std::vector<AxisFeature>& extra = {},
                   const AxisDirectionOptions& direction = {});

  void reset() noexcept;  // both axes at rest (NarxPredictor::reset), no direction yet

  // One tick. `velocity`: the axis reference velocities (v_x, v_y) [mm/s],
  // the networks' inputs. `reference`: R = C(u) in position, and d1, d2 for
  // the local frame of Eqs. 5-6: the path derivatives C'(u), C''(u) from the
  // interpolator, as seed 002 uses them (defined on a regular path even at
  // standstill), or equally the axis velocity and acceleration vectors
  // q' = C'u', q'' = C''u'^2 + C'u'' (same tangent, normal and curvature
  // while the feed u' > 0: kappa = |q' x q''| / |q'|^3 = |C' x C''| / |C'|^3).
  // d3 is not read. Status non_finite_input (any NaN/Inf) or
  // undefined_tangent (d1 = 0).
  PredictorStatus step(const Vec2& velocity, const PathPoint& reference,
                       ContourPrediction& out) noexcept;

  NarxPredictor& axis(std::size_t i) noexcept { return axes_[i]; }  // 0 = x, 1 = y
  const NarxPredictor& axis(std::size_t i) const noexcept { return axes_[i]; }

 private:
  std::array<NarxPredictor, 2> axes_;
  std::array<AxisDirection, 2> directions_;
  std::array<AxisFeature, 3> extra_{};  // the first extra_count_ are used
  std::size_t extra_count_ = 0;
};

}  // namespace cnclab
