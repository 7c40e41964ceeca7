#pragma once
// One face of a STEP or IGES file as our NURBS surface, with its trims and
// orientation for tool-path planning (geometry/tool_path.hpp).
//
// The face's underlying surface, over the face's parameter bounds
// (BRepTools::UVBounds clamped to the surface's own domain: CAD systems
// write bounds a little past it, and a periodic face may span a period plus
// rounding), is converted exactly to a B-spline or NURBS surface by OCCT
// (GeomConvert::SurfaceToBSplineSurface; a B-spline face over its whole knot
// range is taken as it is). The face's trimming loops (outer boundary and
// holes) stay with it as a FaceDomain: OCCT's face classifier
// (BRepTopAdaptor_FClass2d) in the face's own parameters. Lengths are in mm:
// the STEP reader is told the system unit is mm
// (STEPControl_Reader::SetSystemLengthUnit(1)) and converts from the unit the
// file declares; the IGES reader converts to OCCT's session unit (mm unless
// a program changed it), which we scale to mm.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "cnclab/geometry/nurbs_surface.hpp"
#include "cnclab/geometry/tool_path.hpp"

namespace cnclab {

struct CadReadOptions {
  // Wall seconds OCCT's reader may take (it runs in a forked child,
  // io/isolated_read.hpp); 0: default_read_timeout() of the file's size.
  // Dataset options: surface: {file, face, read_timeout}; `cnclab surface
  // --read-timeout`. 0 or in [0.001, 86400].
  double read_timeout = 0;
  void validate() const;
};

// The default read time limit for a file of `bytes`: 60 s plus 10 s per MB.
// OCCT 7.6 read a valid 52.4 MB STEP part of 3,660 faces in 18.6 CPU s and
// 151 s of wall time on a shared 2-core machine under a load of 13 (limit
// 584 s); the wall clock is what the limit measures, so the margin is for
// such machines. A reader that hangs on a damaged file still stops.
double default_read_timeout(std::uintmax_t bytes);

struct CadSurface {
  NurbsSurface surface;      // over the face's parameter bounds [mm]
  std::string file_name;     // as given, for messages only (not the identity)
  std::string file_hash;     // FNV-1a 64 of the file's bytes (core/hash.hpp): the identity
  int face = 1;              // 1-based (cad_format.hpp)
  std::string surface_type;  // the face's own surface before conversion: plane, cylinder, ...
  // label() for messages, the trims (never null once read), the face's
  // orientation and whether it bounds a closed solid.
  FaceContext context;
  bool trimmed = false;  // bounded by more than the iso-lines of its parameter rectangle
  int holes = 0;         // inner loops (wires beyond the outer one)

  // "face 3 of part.step"
  std::string label() const;
};

// (Internal to the cad module: the OCCT shape.)
struct CadShapeData;

// A file read once, its faces converted one at a time.
class CadPart {
 public:
  std::string file_name;  // as given
  std::string file_hash;  // as CadSurface::file_hash
  std::string unit;    // the length unit the file declares (lower case: "millimetre", "inch", "mm")
  std::string writer;  // the CAD system that wrote it, from the header ("" when not given)
  int face_count() const;
  // Face `face` (1..face_count()). ConfigError naming the file and the face
  // when it is out of range or its surface has no NURBS form.
  CadSurface face(int face) const;

  std::shared_ptr<const CadShapeData> shape;  // set by read_cad_part
};

// ConfigError naming the file when it is missing, unreadable, not a CAD
// file, truncated, holds no face or only a mesh, or takes longer than the
// read time limit ("timed out after N s", naming read_timeout); the
// cad_unavailable_message() without OCCT.
CadPart read_cad_part(const std::filesystem::path& file, const CadReadOptions& options = {});

// read_cad_part(file, options).face(face).
CadSurface read_cad_surface(const std::filesystem::path& file, int face,
                            const CadReadOptions& options = {});

}  // namespace cnclab
