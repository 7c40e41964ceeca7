#include "cnclab/motion/feedrate_profile.hpp"

#include <algorithm>

namespace cnclab {

ParameterState FeedrateProfile::at(double time) const {
  const double T = total_time();
  const double tc = std::clamp(time, 0.0, T);
  // Interval k with t[k] <= tc < t[k+1] (the last interval holds tc = T).
  auto it = std::upper_bound(t.begin(), t.end(), tc);
  std::size_t k = static_cast<std::size_t>(std::distance(t.begin(), it));
  k = std::clamp<std::size_t>(k, 1, t.size() - 1) - 1;
  const double tau = tc - t[k], j = uddd[k];
  ParameterState s;
  s.u = u[k] + ud[k] * tau + udd[k] * tau * tau / 2 + j * tau * tau * tau / 6;
  s.ud = ud[k] + udd[k] * tau + j * tau * tau / 2;
  s.udd = udd[k] + j * tau;
  s.uddd = j;
  // Solver tolerance may leave u a hair outside the path at the very end.
  s.u = std::clamp(s.u, u.front(), u.back());
  return s;
}

}  // namespace cnclab
