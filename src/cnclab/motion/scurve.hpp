#pragma once
// Closed-form duration of the jerk-limited rest-to-rest point-to-point motion
// (the "7-phase S-curve": jerk +J, 0, -J, cruise, -J, 0, +J) over a distance
// with velocity, acceleration and jerk bounds. Used as the independent check
// of the feedrate planner on straight lines.

namespace cnclab {

// Minimum time [s] to travel `distance` [mm] from rest to rest with
// |v| <= v_max, |a| <= a_max, |j| <= j_max (all > 0). Cases:
//  - the acceleration limit is reached iff v_peak * j_max >= a_max^2;
//    ramp time to v: v/a + a/j (reached) or 2 sqrt(v/j) (not reached);
//    ramp distance = v * ramp time / 2 (the ramp is point-symmetric);
//  - v_max is reached iff distance >= 2 * ramp distance(v_max); otherwise the
//    peak velocity solves 2 * ramp distance(v) = distance:
//      v^2/a + v a/j = distance          (a reached), or
//      2 v sqrt(v/j) = distance          (a not reached).
double scurve_time(double distance, double v_max, double a_max, double j_max);

}  // namespace cnclab
