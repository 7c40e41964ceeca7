#include "cnclab/studies/contour_error/contour_predictor.hpp"

#include "cnclab/motion/contour_error.hpp"

namespace cnclab {

ContourPredictor::ContourPredictor(NarxAxisModel x, NarxAxisModel y)
    : axes_{NarxPredictor(std::move(x)), NarxPredictor(std::move(y))} {}

void ContourPredictor::reset() noexcept {
  for (NarxPredictor& a : axes_) a.reset();
}

PredictorStatus ContourPredictor::step(const Vec2& velocity, const PathPoint& reference,
                                       ContourPrediction& out) noexcept {
  if (!velocity.allFinite() || !reference.position.allFinite() || !reference.d1.allFinite() ||
      !reference.d2.allFinite()) {
    return PredictorStatus::non_finite_input;
  }
  if (reference.d1.squaredNorm() == 0.0) return PredictorStatus::undefined_tangent;
  Vec2 e;
  for (Eigen::Index i = 0; i < 2; ++i) {
    // Cannot fail: velocity is finite (checked above).
    axes_[static_cast<std::size_t>(i)].step(velocity[i], e[i]);
  }
  out.following_error = e;
  out.actual = reference.position - e;
  out.contour_error = taylor_contour_error(reference, out.actual);
  return PredictorStatus::ok;
}

}  // namespace cnclab
