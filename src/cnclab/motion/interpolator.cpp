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
  const Eigen::Index n = static_cast<Eigen::Index>(std::ceil(T / period - 1e-9)) + 1;
  ReferenceTrajectory r;
  r.period = period;
  r.time.resize(n);
  r.u.resize(n);
  r.position.resize(n, 2);
  r.velocity.resize(n, 2);
  r.acceleration.resize(n, 2);
  r.jerk.resize(n, 2);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = static_cast<double>(k) * period;
    ParameterState s = profile.at(t);
    if (t >= T) s = {profile.u.back(), 0.0, 0.0, 0.0};  // at rest after the end
    const PathPoint p = path.evaluate(s.u);
    r.time[k] = t;
    r.u[k] = s.u;
    r.position.row(k) = p.position.transpose();
    r.velocity.row(k) = (p.d1 * s.ud).transpose();
    r.acceleration.row(k) = (p.d2 * s.ud * s.ud + p.d1 * s.udd).transpose();
    r.jerk.row(k) =
        (p.d3 * s.ud * s.ud * s.ud + 3 * p.d2 * s.ud * s.udd + p.d1 * s.uddd).transpose();
  }
  return r;
}

}  // namespace cnclab
