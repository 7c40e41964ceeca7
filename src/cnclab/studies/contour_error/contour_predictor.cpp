#include "cnclab/studies/contour_error/contour_predictor.hpp"

#include <algorithm>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/contour_error.hpp"

namespace cnclab {

ContourPredictor::ContourPredictor(NarxAxisModel x, NarxAxisModel y,
                                   const std::vector<AxisFeature>& extra,
                                   const AxisDirectionOptions& direction)
    : axes_{NarxPredictor(std::move(x)), NarxPredictor(std::move(y))},
      directions_{AxisDirection(direction), AxisDirection(direction)} {
  if (extra.size() > extra_.size()) {
    throw Error("contour predictor: " + std::to_string(extra.size()) +
                " direction features; there are 3 (sign, direction, reversal)");
  }
  std::copy(extra.begin(), extra.end(), extra_.begin());
  extra_count_ = extra.size();
  for (std::size_t a = 0; a < 2; ++a) {
    if (axes_[a].channels() != 1 + extra_count_) {
      throw Error("contour predictor: the " + std::string(a == 0 ? "x" : "y") + " network has " +
                  std::to_string(axes_[a].channels()) + " input channel(s); the velocity and " +
                  std::to_string(extra_count_) + " direction feature(s) make " +
                  std::to_string(1 + extra_count_));
    }
  }
}

void ContourPredictor::reset() noexcept {
  for (NarxPredictor& a : axes_) a.reset();
  for (AxisDirection& d : directions_) d.reset();
}

PredictorStatus ContourPredictor::step(const Vec2& velocity, const PathPoint& reference,
                                       ContourPrediction& out) noexcept {
  if (!velocity.allFinite() || !reference.position.allFinite() || !reference.d1.allFinite() ||
      !reference.d2.allFinite()) {
    return PredictorStatus::non_finite_input;
  }
  if (reference.d1.squaredNorm() == 0.0) return PredictorStatus::undefined_tangent;
  Vec2 e;
  std::array<double, 4> inputs{};  // the velocity, then the direction features
  for (std::size_t i = 0; i < 2; ++i) {
    directions_[i].step(velocity[static_cast<Eigen::Index>(i)]);
    inputs[0] = velocity[static_cast<Eigen::Index>(i)];
    for (std::size_t f = 0; f < extra_count_; ++f) inputs[1 + f] = directions_[i].value(extra_[f]);
    // Cannot fail: the inputs are finite (checked above), their count the network's.
    axes_[i].step(std::span<const double>(inputs.data(), 1 + extra_count_),
                  e[static_cast<Eigen::Index>(i)]);
  }
  out.following_error = e;
  out.actual = reference.position - e;
  out.contour_error = taylor_contour_error(reference, out.actual);
  return PredictorStatus::ok;
}

}  // namespace cnclab
