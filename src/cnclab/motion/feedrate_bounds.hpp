#pragma once
// Two independent brackets of the jerk-limited minimum traversal time, both
// computed without Ipopt:
//  - a lower bound: the minimum time under velocity and acceleration limits
//    only (no jerk), by the classical forward/backward integration over the
//    path parameter (Bobrow, Dubowsky & Gibson 1985; Shin & McKay 1985);
//  - an upper bound: the time of a feasible profile that ramps with S-curves
//    to the largest constant feedrate the limits allow and back to rest.
#include <limits>

#include "cnclab/motion/axis_limits.hpp"
#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

// Lower bound [s]. With b = (du/dt)^2 and a = d2u/dt2 the axis velocity is
// C'_i sqrt(b) and the axis acceleration C''_i b + C'_i a. On a grid of
// spacing `spacing` mm: b is capped by the maximum-velocity curve (largest b
// with |C'_i| sqrt(b) <= V_i and some a meeting every |C''_i b + C'_i a| <=
// A_i); a forward pass from rest with the largest a and a backward pass
// to rest with the smallest a (db/du = 2a, a constant per interval) give b;
// the time is sum 2 du / (sqrt(b_k) + sqrt(b_k+1)) (exact for constant a).
double velocity_acceleration_time(const PlanarPath& path, const PlanarLimits& limits,
                                  double spacing = 0.05);

struct ConstantFeedrateProfile {
  double time = 0.0;                     // traversal time [s]
  double feedrate = 0.0;                 // cruise path speed F [mm/s]
  double tangential_acceleration = 0.0;  // ramp |dv/dt| bound [mm/s^2]
  double tangential_jerk = 0.0;          // ramp |d2v/dt2| bound [mm/s^3]
};

// Upper bound. With arc length s, speed v = ds/dt, unit tangent T(s):
//   q' = v T,  q'' = dv/dt T + v^2 T',  q''' = d2v/dt2 T + 3 v dv/dt T' + v^3 T''
// (T', T'' by arc length). With m0_i, m1_i, m2_i the maxima of |T_i|, |T'_i|,
// |T''_i| over the path, a profile with v <= F, |dv/dt| <= a_t,
// |d2v/dt2| <= j_t meets every axis limit when
//   F m0_i <= V_i,  a_t m0_i + F^2 m1_i <= A_i,  j_t m0_i + 3 F a_t m1_i + F^3 m2_i <= J_i.
// The S-curve (scurve.hpp) with limits (F, a_t, j_t) over the arc length is
// such a profile; the smallest S-curve time over a grid of F and a_t is
// returned. Maxima are taken on `samples` parameter samples. `max_feed`
// [mm/s] caps F (the best constant-feed profile at most that fast; the
// contour-error study's constant-feed baseline bisects on it).
ConstantFeedrateProfile constant_feedrate_time(
    const PlanarPath& path, const PlanarLimits& limits, int samples = 20001,
    double max_feed = std::numeric_limits<double>::infinity());

}  // namespace cnclab
