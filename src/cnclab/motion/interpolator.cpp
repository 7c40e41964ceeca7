#include "cnclab/motion/interpolator.hpp"

#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {

ReferenceTrajectory interpolate(const PlanarPath& path, const FeedrateProfile& profile,
                                double period) {
  if (!(period > 0.0 && std::isfinite(period))) {
    std::ostringstream m;
    m << "interpolate: period = " << period << " s: must be > 0 and finite";
    throw Error(m.str());
  }
  if (profile.t.size() < 2) throw Error("interpolate: empty feedrate profile");
  const double T = profile.total_time();
  ReferenceTrajectory r = sized_reference_trajectory(T, period);
  for (Eigen::Index k = 0; k < r.samples(); ++k) {
    const double t = r.time[static_cast<std::size_t>(k)];
    ParameterState s = profile.at(t);
    if (t >= T) s = {profile.u.back(), 0.0, 0.0, 0.0};  // at rest after the end
    set_reference_sample(r, k, s.u, path.evaluate(s.u), s.ud, s.udd, s.uddd);
  }
  return r;
}

}  // namespace cnclab
