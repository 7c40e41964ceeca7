#include "cnclab/motion/reference_trajectory.hpp"

#include <cmath>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {

ReferenceTrajectory sized_reference_trajectory(double duration, double period) {
  const Eigen::Index n = static_cast<Eigen::Index>(std::ceil(duration / period - 1e-9)) + 1;
  ReferenceTrajectory r;
  r.period = period;
  r.time.resize(static_cast<std::size_t>(n));
  for (Eigen::Index k = 0; k < n; ++k) {
    r.time[static_cast<std::size_t>(k)] = static_cast<double>(k) * period;
  }
  r.u.resize(static_cast<std::size_t>(n));
  r.position.resize(n, 2);
  r.velocity.resize(n, 2);
  r.acceleration.resize(n, 2);
  r.jerk.resize(n, 2);
  return r;
}

void set_reference_sample(ReferenceTrajectory& r, Eigen::Index k, double u, const PathPoint& p,
                          double ud, double udd, double uddd) {
  r.u[static_cast<std::size_t>(k)] = u;
  r.position.row(k) = p.position.transpose();
  r.velocity.row(k) = (p.d1 * ud).transpose();
  r.acceleration.row(k) = (p.d2 * ud * ud + p.d1 * udd).transpose();
  r.jerk.row(k) = (p.d3 * ud * ud * ud + 3 * p.d2 * ud * udd + p.d1 * uddd).transpose();
}

ReferenceTrajectory concatenate_references(const std::vector<ReferenceTrajectory>& pieces) {
  if (pieces.empty()) throw Error("concatenate_references: no piece");
  Eigen::Index n = 0;
  for (const auto& p : pieces) {
    if (p.period != pieces.front().period) {
      throw Error("concatenate_references: periods differ (" + std::to_string(p.period) + " s, " +
                  std::to_string(pieces.front().period) + " s)");
    }
    n += p.samples();
  }
  ReferenceTrajectory r;
  r.period = pieces.front().period;
  for (Eigen::MatrixX2d* m : {&r.position, &r.velocity, &r.acceleration, &r.jerk}) m->resize(n, 2);
  Eigen::Index row = 0;
  for (const auto& p : pieces) {
    const double shift = row == 0 ? 0.0 : r.time.back() + r.period;
    for (const double t : p.time) r.time.push_back(shift + t);
    r.u.insert(r.u.end(), p.u.begin(), p.u.end());
    r.position.middleRows(row, p.samples()) = p.position;
    r.velocity.middleRows(row, p.samples()) = p.velocity;
    r.acceleration.middleRows(row, p.samples()) = p.acceleration;
    r.jerk.middleRows(row, p.samples()) = p.jerk;
    row += p.samples();
  }
  return r;
}

}  // namespace cnclab
