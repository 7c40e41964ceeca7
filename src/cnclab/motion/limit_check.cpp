#include "cnclab/motion/limit_check.hpp"

#include <algorithm>
#include <cmath>

namespace cnclab {

std::vector<LimitRatios> interval_limit_ratios(const PlanarPath& path,
                                               const FeedrateProfile& profile,
                                               const PlanarLimits& limits, int samples,
                                               std::size_t first, std::size_t last) {
  last = std::min(last, profile.intervals());
  std::vector<LimitRatios> out;
  if (first >= last) return out;
  out.resize(last - first);
  for (std::size_t k = first; k < last; ++k) {
    const double h = profile.t[k + 1] - profile.t[k];
    LimitRatios& r = out[k - first];
    for (int m = 0; m <= samples; ++m) {
      const ParameterState s = profile.in_interval(k, h * m / samples);
      const PathPoint p = path.evaluate(s.u);
      const Vec2 v = p.d1 * s.ud;
      const Vec2 a = p.d2 * s.ud * s.ud + p.d1 * s.udd;
      const Vec2 j = p.d3 * s.ud * s.ud * s.ud + 3 * p.d2 * s.ud * s.udd + p.d1 * s.uddd;
      for (int i = 0; i < 2; ++i) {
        const AxisLimits& L = limits.axes[static_cast<std::size_t>(i)];
        r.velocity[i] = std::max(r.velocity[i], std::abs(v[i]) / L.velocity);
        r.acceleration[i] = std::max(r.acceleration[i], std::abs(a[i]) / L.acceleration);
        r.jerk[i] = std::max(r.jerk[i], std::abs(j[i]) / L.jerk);
      }
    }
  }
  return out;
}

LimitRatios peak_limit_ratios(const std::vector<LimitRatios>& ratios) {
  LimitRatios peak;
  for (const LimitRatios& r : ratios) peak.include(r);
  return peak;
}

}  // namespace cnclab
