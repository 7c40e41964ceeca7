#pragma once
// The fixed-period interpolator: samples a planned feedrate every `period`
// (1 ms as in seed 002) and maps the path parameter to axis references by
// the chain rule:
//   q = C(u),  q' = C' u',  q'' = C'' u'^2 + C' u'',
//   q''' = C''' u'^3 + 3 C'' u' u'' + C' u'''     (' = d/dt on the left).
#include <Eigen/Core>
#include <vector>

#include "cnclab/motion/feedrate_profile.hpp"
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

// Samples k = 0..K, K = ceil(total_time / period); the last sample is the
// end of the path at rest. period > 0.
ReferenceTrajectory interpolate(const PlanarPath& path, const FeedrateProfile& profile,
                                double period = 1e-3);

}  // namespace cnclab
