#pragma once
// Our NURBS surfaces as CAD files (`cnclab surface export`, issue 19 item 2).
#include <string>

#include "cnclab/cad/cad_format.hpp"
#include "cnclab/geometry/nurbs_surface.hpp"

namespace cnclab {

// The text of a STEP (AP214, mm) or IGES (mm) file holding one face: the
// surface as a Geom_BSplineSurface bounded by its parameter rectangle
// (BRepBuilderAPI_MakeFace). Reals are written with 17 significant digits
// (the writers' default is 12), so reading the file gives the same doubles.
// Validates the surface (OptionError).
std::string cad_surface_text(const NurbsSurface& surface, CadFormat format);

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
