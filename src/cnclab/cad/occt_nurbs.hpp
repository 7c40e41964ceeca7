#pragma once
// (Internal to the cad module: OCCT types.) Our NurbsSurface and OCCT's
// Geom_BSplineSurface, and a face's surface in NURBS form.
#include <Geom_BSplineSurface.hxx>
#include <Geom_Surface.hxx>
#include <TopoDS_Face.hxx>
#include <string>

#include "cnclab/geometry/nurbs_surface.hpp"

namespace cnclab::occt {

// Exact copies (same degrees, knots, poles and weights; our flat clamped
// knot vectors are OCCT's distinct knots with multiplicities).
Handle(Geom_BSplineSurface) to_occt(const NurbsSurface& surface);
// Periodic or unclamped surfaces are first made non-periodic (clamped).
NurbsSurface from_occt(const Geom_BSplineSurface& surface);

// The face's parameter rectangle: BRepTools::UVBounds (the box of its
// pcurves) clamped to its surface's domain (CAD systems write pcurves up to
// 1e-3 past it, which GeomConvert rejects), a periodic direction to one period.
struct UvBounds {
  double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
};
UvBounds face_bounds(const TopoDS_Face& face);
// BRepTools::UVBounds as it is.
UvBounds raw_face_bounds(const TopoDS_Face& face);

// The face's surface (with its location) over `bounds` as a B-spline: the
// B-spline itself when the bounds are its whole knot range, else
// GeomConvert::SurfaceToBSplineSurface of the rectangular trim (exact for
// planes, quadrics, tori, surfaces of revolution and extrusion, Bezier and
// B-spline surfaces). Throws Standard_Failure where OCCT has no NURBS form.
Handle(Geom_BSplineSurface) face_nurbs(const TopoDS_Face& face, const UvBounds& bounds);

// Whether face_nurbs keeps the face's parametrisation (B-spline, Bezier and
// plane faces: the conversion only inserts knots or maps linearly);
// otherwise (u, v) of the NURBS form differ from the face's.
bool keeps_parameters(const Handle(Geom_Surface) & surface);

// "plane", "cylinder", "cone", "sphere", "torus", "bezier", "bspline",
// "revolution", "extrusion", "offset", "other"; trims are looked through.
std::string surface_type_name(const Handle(Geom_Surface) & surface);

}  // namespace cnclab::occt
