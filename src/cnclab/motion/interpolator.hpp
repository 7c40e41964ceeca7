#pragma once
// The fixed-period interpolator: samples a planned feedrate every `period`
// (1 ms as in seed 002) and maps the path parameter to axis references by
// the chain rule (reference_trajectory.hpp).
#include "cnclab/motion/feedrate_profile.hpp"
#include "cnclab/motion/planar_path.hpp"
#include "cnclab/motion/reference_trajectory.hpp"

namespace cnclab {

// Samples k = 0..K, K = ceil(total_time / period); the last sample is the
// end of the path at rest. period > 0.
ReferenceTrajectory interpolate(const PlanarPath& path, const FeedrateProfile& profile,
                                double period = 1e-3);

}  // namespace cnclab
