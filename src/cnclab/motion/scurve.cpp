#include "cnclab/motion/scurve.hpp"

#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

double ramp_time(double v, double a, double j) {
  return v * j >= a * a ? v / a + a / j : 2.0 * std::sqrt(v / j);
}

}  // namespace

double scurve_time(double distance, double v_max, double a_max, double j_max) {
  if (!(distance >= 0.0 && v_max > 0.0 && a_max > 0.0 && j_max > 0.0)) {
    std::ostringstream m;
    m << "scurve_time: need distance >= 0 and positive limits, got distance " << distance << ", v "
      << v_max << ", a " << a_max << ", j " << j_max;
    throw Error(m.str());
  }
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

}  // namespace cnclab
