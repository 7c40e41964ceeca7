#pragma once
// Our NURBS surfaces and the faces of CAD files as CAD files (`cnclab surface export`).
#include <string>

#include "cnclab/cad/cad_format.hpp"
#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/geometry/nurbs_surface.hpp"

namespace cnclab {

// The text of a STEP (AP214, mm) or IGES (mm) file holding one face: the
// surface as a Geom_BSplineSurface bounded by its parameter rectangle
// (BRepBuilderAPI_MakeFace). Reals are written with 17 significant digits
// (the writers' default is 12), so reading the file gives the same doubles.
// Validates the surface (OptionError).
std::string cad_surface_text(const NurbsSurface& surface, CadFormat format);

// The text of a STEP or IGES file holding face `face` of `part` alone, as a
// NURBS face with its trims: BRepBuilderAPI_NurbsConvert turns its surface
// and its edges' curves into B-splines (exactly; periodic surfaces become
// clamped ones), keeping its loops, holes and orientation. Read back, it is
// a free face (no longer bounding a solid), so `tool_side: auto` chooses its
// side by the tool axis. ConfigError naming the face as CadPart::face.
std::string cad_face_text(const CadPart& part, int face, CadFormat format);

// The example part of experiments/step_error/cad_example.yaml (the file
// scripts/make_cad_example_part writes): an open shell of four faces of
// different types, in this order:
//   1 `freeform` as a B-spline face,
//   2 a convex cylinder strip (radius 40 mm about an axis parallel to y),
//   3 a plane rectangle,
//   4 a sphere cap (radius 60 mm),
// placed side by side along x.
std::string cad_example_part_text(const NurbsSurface& freeform, CadFormat format);

}  // namespace cnclab
