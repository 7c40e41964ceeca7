#pragma once
// Parameter grids over a planar path with (nearly) equal arc-length spacing:
// the discretisation of the feedrate problem and of the bound computations.
#include <vector>

#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

// Nodes u_0 = u_begin < ... < u_n = u_end with arc length between neighbours
// equal to (arc length / n) to within the table resolution, where
// n = max(min_intervals, ceil(arc length / spacing)). spacing in mm, > 0.
std::vector<double> arc_length_grid(const PlanarPath& path, double spacing, int min_intervals = 1);

}  // namespace cnclab
