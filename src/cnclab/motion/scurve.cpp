#include "cnclab/motion/scurve.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

double ramp_time(double v, double a, double j) {
  return v * j >= a * a ? v / a + a / j : 2.0 * std::sqrt(v / j);
}

// Peak speed of the minimum-time motion: v_max, or the speed whose two
// ramps cover the distance exactly.
double scurve_peak_speed(double distance, double v_max, double a_max, double j_max) {
  if (distance >= v_max * ramp_time(v_max, a_max, j_max)) return v_max;
  // Try "a reached": v^2/a + (a/j) v - distance = 0.
  const double b = a_max / j_max;
  double v = 0.5 * a_max * (-b + std::sqrt(b * b + 4.0 * distance / a_max));
  if (v * j_max < a_max * a_max) v = std::cbrt(0.25 * distance * distance * j_max);
  return v;
}

void check_scurve_arguments(double distance, double v_max, double a_max, double j_max) {
  if (!(distance >= 0.0 && v_max > 0.0 && a_max > 0.0 && j_max > 0.0)) {
    std::ostringstream m;
    m << "scurve_time: need distance >= 0 and positive limits, got distance " << distance << ", v "
      << v_max << ", a " << a_max << ", j " << j_max;
    throw Error(m.str());
  }
}

}  // namespace

double scurve_time(double distance, double v_max, double a_max, double j_max) {
  check_scurve_arguments(distance, v_max, a_max, j_max);
  const double t_ramp = ramp_time(v_max, a_max, j_max);
  const double d_ramp = 0.5 * v_max * t_ramp;
  if (distance >= 2.0 * d_ramp) return 2.0 * t_ramp + (distance - 2.0 * d_ramp) / v_max;
  // Peak velocity below v_max. Try "a reached": v^2/a + (a/j) v - distance = 0.
  const double b = a_max / j_max;
  double v = 0.5 * a_max * (-b + std::sqrt(b * b + 4.0 * distance / a_max));
  if (v * j_max < a_max * a_max)
    v = std::cbrt(0.25 * distance * distance * j_max);  // 2v sqrt(v/j) = d
  return 2.0 * ramp_time(v, a_max, j_max);
}

ScurveState scurve_state(double distance, double v_max, double a_max, double j_max, double t) {
  check_scurve_arguments(distance, v_max, a_max, j_max);
  ScurveState st;
  if (distance == 0.0) return st;
  const double v_p = scurve_peak_speed(distance, v_max, a_max, j_max);
  const bool a_reached = v_p * j_max >= a_max * a_max;
  const double t_j = a_reached ? a_max / j_max : std::sqrt(v_p / j_max);
  const double t_a = a_reached ? v_p / a_max - t_j : 0.0;
  const double ramp = 2.0 * t_j + t_a;
  const double t_c = std::max(0.0, (distance - v_p * ramp) / v_p);
  const double durations[7] = {t_j, t_a, t_j, t_c, t_j, t_a, t_j};
  const double jerks[7] = {j_max, 0.0, -j_max, 0.0, -j_max, 0.0, j_max};
  double left = std::max(0.0, t);
  for (int k = 0; k < 7; ++k) {
    const double h = std::min(left, durations[k]), j = jerks[k];
    st.s += st.v * h + st.a * h * h / 2 + j * h * h * h / 6;
    st.v += st.a * h + j * h * h / 2;
    st.a += j * h;
    st.j = j;
    left -= h;
    if (left <= 0.0) break;
  }
  if (left > 0.0) st = {distance, 0.0, 0.0, 0.0};  // after the end: at rest
  st.s = std::clamp(st.s, 0.0, distance);
  return st;
}

}  // namespace cnclab
