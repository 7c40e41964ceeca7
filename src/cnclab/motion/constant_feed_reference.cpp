#include "cnclab/motion/constant_feed_reference.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/path_grid.hpp"
#include "cnclab/motion/reference_trajectory.hpp"
#include "cnclab/motion/scurve.hpp"

namespace cnclab {
namespace {

// Arc length -> parameter: a table every ~0.02 mm, linear between its rows,
// then one Newton step on s(u) - s with ds/du = |C'(u)| (the table error is
// second order in its spacing; the step squares it).
class ConstantFeedArcInverse {
 public:
  explicit ConstantFeedArcInverse(const PlanarPath& path) : path_(path) {
    u_ = arc_length_grid(path, 0.02, 2);
    s_.assign(u_.size(), 0.0);
    for (std::size_t k = 0; k + 1 < u_.size(); ++k) {
      s_[k + 1] = s_[k] + arc_length(path, u_[k], u_[k + 1], 1);
    }
  }
  double length() const { return s_.back(); }
  double parameter(double s) const {
    s = std::clamp(s, 0.0, s_.back());
    auto it = std::upper_bound(s_.begin(), s_.end(), s);
    std::size_t k = static_cast<std::size_t>(it - s_.begin());
    k = std::clamp<std::size_t>(k, 1, s_.size() - 1) - 1;
    const double w = (s - s_[k]) / (s_[k + 1] - s_[k]);
    double u = u_[k] + w * (u_[k + 1] - u_[k]);
    const double s_u = s_[k] + arc_length(path_, u_[k], u, 1);
    u -= (s_u - s) / path_.evaluate(u).d1.norm();
    return std::clamp(u, path_.u_begin(), path_.u_end());
  }

 private:
  const PlanarPath& path_;
  std::vector<double> u_, s_;
};

}  // namespace

ReferenceTrajectory constant_feed_reference(const PlanarPath& path,
                                            const ConstantFeedrateProfile& profile, double period) {
  if (!(profile.feedrate > 0 && profile.tangential_acceleration > 0 &&
        profile.tangential_jerk > 0 && period > 0)) {
    std::ostringstream m;
    m << "constant_feed_reference: need feed, acceleration, jerk and period > 0, got "
      << profile.feedrate << ", " << profile.tangential_acceleration << ", "
      << profile.tangential_jerk << ", " << period;
    throw Error(m.str());
  }
  const ConstantFeedArcInverse inverse(path);
  const double L = inverse.length();
  const double F = profile.feedrate, A = profile.tangential_acceleration;
  const double J = profile.tangential_jerk;
  const double T = scurve_time(L, F, A, J);
  ReferenceTrajectory r = sized_reference_trajectory(T, period);
  for (Eigen::Index k = 0; k < r.samples(); ++k) {
    const double t = r.time[static_cast<std::size_t>(k)];
    const ScurveState st = t >= T ? ScurveState{L, 0, 0, 0} : scurve_state(L, F, A, J, t);
    const double u = inverse.parameter(st.s);
    const PathPoint p = path.evaluate(u);
    const double sigma = p.d1.norm();
    const Vec2 tangent = p.d1 / sigma;
    const double tc2 = tangent.dot(p.d2);
    const Vec2 dtangent = (p.d2 - tangent * tc2) / sigma;
    const double ud = st.v / sigma;
    const double udd = (st.a - tc2 * ud * ud) / sigma;
    const double uddd =
        (st.j - (dtangent.dot(p.d2) + tangent.dot(p.d3)) * ud * ud * ud - 3 * tc2 * ud * udd) /
        sigma;
    set_reference_sample(r, k, u, p, ud, udd, uddd);
  }
  return r;
}

}  // namespace cnclab
