#pragma once
// Direction features of one axis's commanded velocity, tick by tick: what a
// following-error predictor needs to see the errors that come with a change
// of direction (docs/motion.md, simulated feed drive: Coulomb/Stribeck
// friction and stiction act against the sign of the velocity, backlash takes
// the table to the other side of the gap), which the velocity alone, a few
// ticks of it, does not show: near a reversal v is close to 0 on both sides.
//
//   sign      s(t) = sgn v(t), 0 while |v(t)| <= deadband (at rest)
//   direction d(t) = the sign of the last commanded velocity outside the
//             deadband (the side of the backlash gap the table was pushed
//             to, the direction friction last acted in); 0 before any motion
//   reversal  r(t) = d(t) exp(-(t - t_c) / tau), t_c the tick at which d
//             last changed (0 -> +-1 included): a decaying pulse that tells
//             the network how long ago the direction changed, over the few
//             servo time constants the stick-slip transient lasts
//             (1/Kp = 25 ms at the router's Kp = 40 1/s); 0 before any motion
//   since_change  t - t_c [s], infinity before any motion (the feedrate
//             loop's margins after a reversal, margin_calibration.hpp)
//
// Every feature is in [-1, 1] by construction (a network input needs no
// normalisation). The dataset generator (data/following_error.hpp) and the
// real-time contour predictor compute them with this one class, so training
// and prediction see the same values. step() never allocates or throws.
#include <cstddef>
#include <string>
#include <vector>

namespace cnclab {

enum class AxisFeature { sign, direction, reversal };
// "sign", "direction", "reversal" (the dataset's input names before _x/_y).
const char* to_string(AxisFeature feature) noexcept;
// The feature named `name`; false when there is none.
bool parse_axis_feature(const std::string& name, AxisFeature& out) noexcept;

struct AxisDirectionOptions {
  // |v| at or below this is standstill [mm/s], >= 0 (the interpolator's v
  // is exactly 0 at rest; crossing 0 at a reversal takes one tick).
  double deadband = 1e-3;
  // tau of the reversal pulse [s], > 0.
  double reversal_time_constant = 0.02;
  double period = 1e-3;  // tick [s] (the controller period), > 0

  void validate() const;  // OptionError naming the field
};

class AxisDirection {
 public:
  explicit AxisDirection(AxisDirectionOptions options = {});  // validates

  // Before any motion: every feature 0.
  void reset() noexcept;
  // One tick with the commanded velocity v(t) [mm/s]; a non-finite v is
  // taken as standstill for the sign and leaves the direction as it was.
  void step(double velocity) noexcept;

  double sign() const noexcept { return sign_; }
  double direction() const noexcept { return direction_; }
  double reversal() const noexcept;
  double value(AxisFeature feature) const noexcept;
  // Time since d last changed, t - t_c [s]: 0 at the tick of the change,
  // infinity before any motion.
  double since_change() const noexcept;

 private:
  AxisDirectionOptions options_;
  double sign_ = 0.0, direction_ = 0.0;
  double decay_ = 1.0;                 // exp(-(t - t_c) / tau) at the current tick
  long long ticks_since_change_ = -1;  // -1: no motion yet
  double per_tick_ = 1.0;
};

// The features of a whole velocity series from rest, one vector per feature
// in `features` order.
std::vector<std::vector<double>> axis_direction_series(const std::vector<double>& velocity,
                                                       const std::vector<AxisFeature>& features,
                                                       const AxisDirectionOptions& options);

}  // namespace cnclab
