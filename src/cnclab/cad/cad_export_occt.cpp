// cad_surface_text and cad_example_part_text with OCCT (cad_export.hpp).
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Precision.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Sphere.hxx>
#include <numbers>

#include "cnclab/cad/cad_export.hpp"
#include "cnclab/cad/occt_nurbs.hpp"
#include "cnclab/cad/occt_part.hpp"
#include "cnclab/cad/occt_shape_io.hpp"
#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

TopoDS_Face nurbs_face(const NurbsSurface& surface) {
  BRepBuilderAPI_MakeFace make(occt::to_occt(surface), Precision::Confusion());
  if (!make.IsDone()) throw Error("OCCT could not make a face of the NURBS surface");
  return make.Face();
}

}  // namespace

std::string cad_surface_text(const NurbsSurface& surface, CadFormat format) {
  return occt::cad_shape_text(nurbs_face(surface), format);
}

std::string cad_face_text(const CadPart& part, int face, CadFormat format) {
  const TopoDS_Face& f = occt::part_face(part, face);
  const std::string label = "face " + std::to_string(face) + " of " + part.file_name;
  if (BRep_Tool::Surface(f).IsNull()) throw ConfigError(label + ": has no surface (a mesh face)");
  TopoDS_Shape nurbs;
  try {
    BRepBuilderAPI_NurbsConvert convert(f, true);
    if (!convert.IsDone()) throw Error("not done");
    nurbs = convert.Shape();
  } catch (...) {
    throw ConfigError(label + ": OCCT could not convert it to NURBS (" + occt::occt_failure_text() +
                      ")");
  }
  return occt::cad_shape_text(nurbs, format);
}

std::string cad_example_part_text(const NurbsSurface& freeform, CadFormat format) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  // Frames whose u runs in the x-z plane and v along y, so that tool-path
  // lines (constant v) run across each face in x like the paper's paths.
  const gp_Dir x(1, 0, 0), minus_y(0, -1, 0);
  // Cylinder strip: radius 40 about the line x = 200, z = -10 (parallel to
  // y), angles 60..120 deg (convex toward +z), 50 mm long.
  const gp_Cylinder cylinder(gp_Ax3(gp_Pnt(200, 0, -10), minus_y, x), 40.0);
  // Plane rectangle 40 x 50 mm from (260, 0, 10), tilted 10 deg about y.
  const gp_Ax3 plane_frame(gp_Pnt(260, 0, 10), gp_Dir(-std::sin(10 * kDeg), 0, std::cos(10 * kDeg)),
                           gp_Dir(std::cos(10 * kDeg), 0, std::sin(10 * kDeg)));
  // Sphere cap: radius 60 about (360, 25, -40); u (longitude) about z, v
  // (latitude) 60..80 deg.
  const gp_Sphere sphere(gp_Ax3(gp_Pnt(360, 25, -40), gp_Dir(0, 0, 1), x), 60.0);
  const TopoDS_Face faces[] = {
      nurbs_face(freeform),
      BRepBuilderAPI_MakeFace(cylinder, 60 * kDeg, 120 * kDeg, -50, 0).Face(),
      BRepBuilderAPI_MakeFace(gp_Pln(plane_frame), 0, 40, 0, 50).Face(),
      BRepBuilderAPI_MakeFace(sphere, -30 * kDeg, 30 * kDeg, 50 * kDeg, 75 * kDeg).Face(),
  };
  TopoDS_Compound part;
  BRep_Builder builder;
  builder.MakeCompound(part);
  for (const TopoDS_Face& f : faces) builder.Add(part, f);
  return occt::cad_shape_text(part, format);
}

}  // namespace cnclab
