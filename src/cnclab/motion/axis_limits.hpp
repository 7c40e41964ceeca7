#pragma once
// Kinematic limits of one machine axis. Defaults: seed 002, Sec. II ("maximum
// velocity (300 mm/s), acceleration (2000 mm/s2) and jerk (50000 mm/s3)").
#include <array>

namespace cnclab {

struct AxisLimits {
  double velocity = 300.0;       // max |axis velocity| [mm/s], > 0
  double acceleration = 2000.0;  // max |axis acceleration| [mm/s^2], > 0
  double jerk = 50000.0;         // max |axis jerk| [mm/s^3], > 0

  void validate() const;
};

// Limits of the two axes (x, y) of a planar machine.
struct PlanarLimits {
  std::array<AxisLimits, 2> axes{};  // [0] = x, [1] = y

  // Names the axis in the field: "axes[1].jerk = -1: must be > 0 and finite".
  void validate() const;
};

}  // namespace cnclab
