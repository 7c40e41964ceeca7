#pragma once
// The faces of a STEP or IGES file and whether each gives a tool path, for
// `cnclab surface show`.
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/geometry/tool_path.hpp"

namespace cnclab {

struct CadShowOptions {
  CadReadOptions read;
  // The path each face is planned with for its verdict: a 50 x 50 probe by
  // default (the verdict is a path's: a denser path can meet a gouge or a
  // thin part of the face that a sparse one misses).
  ToolPathOptions path = probe_path();

  static ToolPathOptions probe_path() {
    ToolPathOptions o;
    o.lines = o.points_per_line = 50;
    return o;
  }
};

struct CadFaceSummary {
  int index = 1;                   // 1-based (cad_format.hpp)
  std::string surface_type;        // plane, cylinder, cone, sphere, torus, bspline, bezier, ...
  int degree_u = 0, degree_v = 0;  // of the face's NURBS form (0: no NURBS form)
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;               // parameter bounds (clamped UVBounds)
  double area = 0;                                     // [mm^2] (BRepGProp::SurfaceProperties)
  Eigen::Vector3d box_min{0, 0, 0}, box_max{0, 0, 0};  // [mm] (BRepBndLib, optimal)
  bool trimmed = false;                                // CadSurface::trimmed
  int holes = 0;                                       // inner loops
  bool of_solid = false;                               // bounds a closed solid
  // OCCT's own evaluation (BRepLProp_SLProps) at a 25 x 25 grid of the
  // face's parameters, the points on the face: the normal on the side the
  // tool works from (as the planner decides it; the face's own normal when
  // it has no NURBS form) dotted with the tool axis, and the smallest radius
  // of curvature, concave or convex seen from that side (infinite: planar).
  double axis_min = 0, axis_max = 0;
  double min_radius = 0;
  bool min_radius_concave = false;
  // The verdict of the path options: "yes", or the refusal's reason
  // (refusal_name, "no NURBS form", ...), and `reason_text` its message.
  std::string usable, reason_text;
  // With unreachable: clip: the share of the path's CC points left on it
  // (0..1), or -1 where that is refused too (reason in clip_usable).
  double clip_share = -1;
  std::string clip_usable;
};

struct CadPartSummary {
  std::string unit;                   // CadPart::unit
  std::string writer;                 // CadPart::writer
  std::vector<CadFaceSummary> faces;  // in file order
};

// Every face in file order. ConfigError as read_cad_part.
CadPartSummary summarise_cad_part(const std::filesystem::path& file,
                                  const CadShowOptions& options = {});

}  // namespace cnclab
