#include "cnclab/motion/feedrate_profile.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

double LimitRatios::worst() const {
  return std::max({velocity[0], velocity[1], acceleration[0], acceleration[1], jerk[0], jerk[1]});
}

void LimitRatios::include(const LimitRatios& o) {
  for (int i = 0; i < 2; ++i) {
    velocity[i] = std::max(velocity[i], o.velocity[i]);
    acceleration[i] = std::max(acceleration[i], o.acceleration[i]);
    jerk[i] = std::max(jerk[i], o.jerk[i]);
  }
}

ParameterState FeedrateProfile::at(double time) const {
  const double T = total_time();
  const double tc = std::clamp(time, 0.0, T);
  // Interval k with t[k] <= tc < t[k+1] (the last interval holds tc = T).
  auto it = std::upper_bound(t.begin(), t.end(), tc);
  std::size_t k = static_cast<std::size_t>(std::distance(t.begin(), it));
  k = std::clamp<std::size_t>(k, 1, t.size() - 1) - 1;
  return in_interval(k, tc - t[k]);
}

ParameterState FeedrateProfile::in_interval(std::size_t k, double tau) const {
  const double j = uddd[k];
  ParameterState s;
  s.u = u[k] + ud[k] * tau + udd[k] * tau * tau / 2 + j * tau * tau * tau / 6;
  s.ud = ud[k] + udd[k] * tau + j * tau * tau / 2;
  s.udd = udd[k] + j * tau;
  s.uddd = j;
  // Solver tolerance may leave u a hair outside the path at the very end.
  s.u = std::clamp(s.u, u.front(), u.back());
  return s;
}

FeedrateProfile time_scaled(const FeedrateProfile& profile, double factor) {
  if (!(factor > 0.0 && factor <= 1.0)) {
    throw OptionError("factor", shortest_double(factor), "must be in (0, 1]");
  }
  FeedrateProfile out;
  out.u = profile.u;
  out.t.resize(profile.t.size());
  out.ud.resize(profile.ud.size());
  out.udd.resize(profile.udd.size());
  out.uddd.resize(profile.uddd.size());
  for (std::size_t k = 0; k < profile.t.size(); ++k) {
    out.t[k] = profile.t[k] / factor;
    out.ud[k] = profile.ud[k] * factor;
    out.udd[k] = profile.udd[k] * factor * factor;
  }
  for (std::size_t k = 0; k < profile.uddd.size(); ++k) {
    out.uddd[k] = profile.uddd[k] * factor * factor * factor;
  }
  return out;
}

}  // namespace cnclab
