#pragma once

#include <numbers>

// Unit conversions shared by the data generators and the studies.
namespace cnclab {

// Micrometres per millimetre: step and following errors are computed in mm
// (the machine's unit) and reported in µm (the papers' unit).
inline constexpr double kUmPerMm = 1000.0;

// Degrees per radian: angles are computed in radians and reported in degrees.
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;

}  // namespace cnclab
