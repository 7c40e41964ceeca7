#pragma once
// The axis limits checked on a planned feedrate between its grid nodes. The
// planner imposes the limits at the nodes only; in between, the exact cubic
// motion of each interval (u(t) with constant d3u/dt3) follows the path
// geometry, and the axis derivatives (chain rule, interpolator.hpp)
//   q' = C' u',  q'' = C'' u'^2 + C' u'',  q''' = C''' u'^3 + 3 C'' u' u'' + C' u'''
// can exceed the limits there. The check samples them at samples + 1 equally
// spaced instants of every interval, both ends included (the jerk at an end
// with that interval's u'''), and divides by the limits.
#include <cstddef>
#include <limits>
#include <vector>

#include "cnclab/motion/axis_limits.hpp"
#include "cnclab/motion/feedrate_profile.hpp"
#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

// Peak ratios of each interval k in [first, min(last, intervals)), in order.
// samples >= 1.
std::vector<LimitRatios> interval_limit_ratios(
    const PlanarPath& path, const FeedrateProfile& profile, const PlanarLimits& limits, int samples,
    std::size_t first = 0, std::size_t last = std::numeric_limits<std::size_t>::max());

// Elementwise maximum over the intervals (all zero for none).
LimitRatios peak_limit_ratios(const std::vector<LimitRatios>& ratios);

}  // namespace cnclab
