#pragma once
// One face of a STEP or IGES file as our NURBS surface (issue 19 item 1).
//
// The face's underlying surface, trimmed to the face's parameter bounds
// (BRepTools::UVBounds), is converted exactly to a B-spline or NURBS surface
// by OCCT (GeomConvert::SurfaceToBSplineSurface; a B-spline face over its
// whole knot range is taken as it is). Lengths are in mm: the STEP reader is
// told the system unit is mm (STEPControl_Reader::SetSystemLengthUnit(1)) and
// converts from the unit the file declares; the IGES reader converts to
// OCCT's session unit (mm unless a program changed it), which we scale to mm.
#include <Eigen/Core>
#include <filesystem>
#include <memory>
#include <string>

#include "cnclab/geometry/nurbs_surface.hpp"
#include "cnclab/geometry/tool_path.hpp"

namespace cnclab {

// The face's trimmed domain (its wires), for checking tool paths.
class CadFaceBoundary {
 public:
  virtual ~CadFaceBoundary() = default;
  // Whether the point S(u, v) of `surface` (CadSurface::surface) lies on the
  // face (inside or on its boundary, to the face's tolerance). Evaluates
  // S(u, v) only where the face's own parameters differ from the NURBS
  // form's (a B-spline face keeps them: a 2-D test on (u, v) alone).
  virtual bool contains(const NurbsSurface& surface, double u, double v) const = 0;
};

struct CadSurface {
  NurbsSurface surface;      // over the face's parameter bounds [mm]
  std::string file_name;     // as given, for messages only (not the identity)
  std::string file_hash;     // FNV-1a 64 of the file's bytes (core/hash.hpp): the identity
  int face = 1;              // 1-based (cad_format.hpp)
  std::string surface_type;  // the face's own surface before conversion: plane, cylinder, ...
  std::shared_ptr<const CadFaceBoundary> boundary;  // never null once read

  // "face 3 of part.step"
  std::string label() const;
};

// Reads face `face` of `file` (STEP or IGES by extension). ConfigError naming
// the file (and the face) when the file is missing, unreadable, not a CAD
// file, truncated, has no faces, `face` is out of range, or its surface has
// no NURBS form; the cad_unavailable_message() without OCCT.
CadSurface read_cad_surface(const std::filesystem::path& file, int face);

// ConfigError naming the face, the line and the CC point when a CC point of
// the tool path `options` plans on cad.surface (geometry/tool_path.hpp) lies
// off the face: a path over a trimmed face's parameter rectangle must not
// run past the trimming curves silently.
void check_tool_path_on_face(const CadSurface& cad, const ToolPathOptions& options);

}  // namespace cnclab
