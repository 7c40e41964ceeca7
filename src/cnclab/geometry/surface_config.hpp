#pragma once
// NURBS surfaces in YAML (configs/surfaces/*.yaml):
//   degree_u: 3                 # p
//   degree_v: 3                 # q
//   knots_u: [0, 0, 0, 0, ...]  # clamped, count_u + p + 1 values
//   knots_v: [...]              # clamped, count_v + q + 1 values
//   control_points:             # count_u rows (along u), each count_v [x, y, z] in mm
//     - [[0, 0, 1.5], [0, 20, 2.0], ...]
//   weights:                    # optional, same shape, > 0 (default all 1)
//     - [1, 1, ...]
// count_u and count_v are the shape of control_points.
#include <string>

#include "cnclab/core/config.hpp"
#include "cnclab/geometry/nurbs_surface.hpp"

namespace cnclab {

// Strict: unknown keys, ragged rows, points that are not [x, y, z] and every
// NurbsSurface::validate() rule are ConfigErrors naming the file position.
NurbsSurface read_nurbs_surface(const ConfigReader& r);

// The same layout as YAML block text (numbers in shortest round-trip form,
// core/format.hpp), each line prefixed by `indent`; reading it back gives
// the identical surface.
std::string nurbs_surface_yaml(const NurbsSurface& surface, const std::string& indent);

}  // namespace cnclab
