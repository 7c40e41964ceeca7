// The closed-form S-curve time against a direct time-stepped simulation of
// the 7-phase jerk profile (independent: integrates the phases numerically).
#include "cnclab/motion/scurve.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

// Distance covered by the symmetric 7-phase profile with jerk phase tj,
// constant-acceleration phase ta and cruise tv, integrated with small steps.
double simulated_distance(double j, double tj, double ta, double tv, double* v_peak) {
  const double phases[7] = {tj, ta, tj, tv, tj, ta, tj};
  const double jerks[7] = {j, 0, -j, 0, -j, 0, j};
  double x = 0, v = 0, a = 0;
  *v_peak = 0;
  for (int p = 0; p < 7; ++p) {
    const int steps = 20000;
    const double dt = phases[p] / steps;
    for (int s = 0; s < steps; ++s) {  // exact for piecewise-constant jerk
      x += v * dt + a * dt * dt / 2 + jerks[p] * dt * dt * dt / 6;
      v += a * dt + jerks[p] * dt * dt / 2;
      a += jerks[p] * dt;
      *v_peak = std::max(*v_peak, v);
    }
  }
  return x;
}

constexpr double kV = 300, kA = 2000, kJ = 50000;

TEST(SCurve, AllCasesMatchPhaseIntegration) {
  // Cases: v and a reached; a reached, v not; neither reached; v reached, a not.
  struct Case {
    double distance, v, a, j;
  };
  for (const Case c : {Case{200, kV, kA, kJ}, Case{20, kV, kA, kJ}, Case{0.5, kV, kA, kJ},
                       Case{200, 50, kA, kJ}}) {
    const double T = scurve_time(c.distance, c.v, c.a, c.j);
    // Rebuild the phases from T by the same case logic written in terms of
    // phase durations: search the peak velocity that the integrated profile
    // needs to cover the distance, then compare durations.
    double lo = 0, hi = c.v;
    double tj = 0, ta = 0, tv = 0, vp = 0;
    for (int it = 0; it < 60; ++it) {
      const double vm = 0.5 * (lo + hi);
      const double am = std::min(c.a, std::sqrt(vm * c.j));
      tj = am / c.j;
      ta = vm / am - tj;
      const double d_ramps = simulated_distance(c.j, tj, ta, 0.0, &vp);
      (d_ramps <= c.distance ? lo : hi) = vm;
    }
    const double am = std::min(c.a, std::sqrt(lo * c.j));
    tj = am / c.j;
    ta = lo / am - tj;
    const double d_ramps = simulated_distance(c.j, tj, ta, 0.0, &vp);
    tv = (c.distance - d_ramps) / lo;
    const double t_sim = 4 * tj + 2 * ta + tv;
    EXPECT_NEAR(T, t_sim, 1e-6 * t_sim) << "distance " << c.distance << " v " << c.v;
    EXPECT_NEAR(simulated_distance(c.j, tj, ta, tv, &vp), c.distance, 1e-6 * c.distance);
  }
}

TEST(SCurve, KnownValue) {
  // 200 mm at seed 002's limits: ramp 300/2000 + 2000/50000 = 0.19 s over
  // 28.5 mm; cruise (200 - 57)/300 s.
  EXPECT_NEAR(scurve_time(200, kV, kA, kJ), 2 * 0.19 + 143.0 / 300.0, 1e-12);
}

TEST(SCurve, RejectsBadLimits) {
  EXPECT_THROW(scurve_time(1, 0, kA, kJ), Error);
  EXPECT_THROW(scurve_time(-1, kV, kA, kJ), Error);
  EXPECT_THROW(scurve_time(1, kV, kA, std::nan("")), Error);
}

}  // namespace
}  // namespace cnclab
