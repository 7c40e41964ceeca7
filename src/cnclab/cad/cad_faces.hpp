#pragma once
// The faces of a STEP or IGES file, for `cnclab surface show` (issue 19 item 2).
#include <Eigen/Core>
#include <filesystem>
#include <string>
#include <vector>

namespace cnclab {

struct CadFaceSummary {
  int index = 1;                   // 1-based (cad_format.hpp)
  std::string surface_type;        // plane, cylinder, cone, sphere, torus, bspline, bezier, ...
  int degree_u = 0, degree_v = 0;  // of the face's NURBS form (0: no NURBS form)
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;               // parameter bounds (BRepTools::UVBounds)
  double area = 0;                                     // [mm^2] (BRepGProp::SurfaceProperties)
  Eigen::Vector3d box_min{0, 0, 0}, box_max{0, 0, 0};  // [mm] (BRepBndLib, optimal)
};

// Every face in file order. ConfigError as read_cad_surface (cad_surface.hpp).
std::vector<CadFaceSummary> list_cad_faces(const std::filesystem::path& file);

}  // namespace cnclab
