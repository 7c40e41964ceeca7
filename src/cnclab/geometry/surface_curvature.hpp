#pragma once
// Curvatures of a surface at a point from its first and second fundamental
// forms (do Carmo, "Differential Geometry of Curves and Surfaces", 3-2, 3-3):
//   I = [E F; F G] = [S_u.S_u  S_u.S_v; S_u.S_v  S_v.S_v],
//   II = [L M; M N] = [S_uu.n  S_uv.n; S_uv.n  S_vv.n],
// the normal curvature in the tangent direction w = a S_u + b S_v is
//   k(w) = (L a^2 + 2 M a b + N b^2) / (E a^2 + 2 F a b + G b^2),
// and the principal curvatures are H +- sqrt(H^2 - K) with
//   H = (E N - 2 F M + G L) / (2 (E G - F^2)),  K = (L N - M^2) / (E G - F^2).
// Signs follow n: k > 0 where the surface bends toward n, i.e. it is concave
// seen from the side n points to (a ball on that side of radius R > 1/k
// cannot touch the surface there without cutting into it).
#include <Eigen/Core>

#include "cnclab/geometry/nurbs_surface.hpp"

namespace cnclab {

struct SurfaceCurvatures {
  double along = 0.0;   // normal curvature along the given tangent direction [1/mm]
  double across = 0.0;  // along n x that direction (the other tangent) [1/mm]
  double max = 0.0;     // the larger principal curvature [1/mm]
  double min = 0.0;     // the smaller principal curvature [1/mm]
};

// At the point of `d`, n its unit normal (either side: the signs follow it)
// and `along` a tangent vector (any length; e.g. S_u for a feed along u).
// The surface must be regular there (S_u x S_v != 0).
SurfaceCurvatures surface_curvatures(const SurfaceDerivatives& d, const Eigen::Vector3d& n,
                                     const Eigen::Vector3d& along);

}  // namespace cnclab
