#pragma once
// The sampled axis reference of a planned motion, what the interpolators
// (interpolate(), constant_feed_reference()) hand the feed drives: every
// `period`, the path parameter and the axis position with its first three
// time derivatives, by the chain rule
//   q = C(u),  q' = C' u',  q'' = C'' u'^2 + C' u'',
//   q''' = C''' u'^3 + 3 C'' u' u'' + C' u'''     (' = d/dt on the left).
#include <Eigen/Core>
#include <vector>

#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

struct ReferenceTrajectory {
  double period = 1e-3;           // sample period [s]
  std::vector<double> time;       // k * period [s]
  std::vector<double> u;          // path parameter at each sample
  Eigen::MatrixX2d position;      // [mm], one row per sample, columns x, y
  Eigen::MatrixX2d velocity;      // [mm/s]
  Eigen::MatrixX2d acceleration;  // [mm/s^2]
  Eigen::MatrixX2d jerk;          // [mm/s^3]

  Eigen::Index samples() const { return position.rows(); }
};

// A trajectory of `duration` T [s] sampled every `period` [s]: samples
// k = 0..K, K = ceil(T / period - 1e-9) (the 1e-9 keeps a T that is a whole
// number of periods, up to rounding, from gaining a sample), so the last
// sample is at or after T. time[k] = k period; u and the axis rows are
// allocated, for set_reference_sample() to fill. period > 0 (the callers
// check it and name themselves).
ReferenceTrajectory sized_reference_trajectory(double duration, double period);

// Sample k (< r.samples()) at path parameter u, C and its u-derivatives `p`
// there, and the parameter's time derivatives u' = ud, u'' = udd,
// u''' = uddd: position and its derivatives by the chain rule above.
void set_reference_sample(ReferenceTrajectory& r, Eigen::Index k, double u, const PathPoint& p,
                          double ud, double udd, double uddd);

// `pieces` one after the other: piece i + 1's samples follow piece i's last
// sample by one period (its time shifted), rows appended as they are. Meant
// for motions that end and start at rest where they meet (plans of
// consecutive sections of a path: the machine stops at each joint for a
// tick). cnclab::Error when the periods differ or there is no piece.
ReferenceTrajectory concatenate_references(const std::vector<ReferenceTrajectory>& pieces);

}  // namespace cnclab
