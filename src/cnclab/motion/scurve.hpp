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

// The same motion at time t in [0, scurve_time(...)] (clamped): distance s,
// speed v, acceleration a and jerk j. Seven phases of constant jerk
// (+J, 0, -J, 0, -J, 0, +J) of durations t_j, t_a, t_j, t_c, t_j, t_a, t_j with
// t_j = a_max/j_max, t_a = v_p/a_max - t_j when the acceleration limit is
// reached (else t_j = sqrt(v_p/j_max), t_a = 0), v_p the peak speed and t_c
// the cruise; integrated exactly phase by phase. Throws as scurve_time.
struct ScurveState {
  double s = 0.0, v = 0.0, a = 0.0, j = 0.0;
};
ScurveState scurve_state(double distance, double v_max, double a_max, double j_max, double t);

}  // namespace cnclab
