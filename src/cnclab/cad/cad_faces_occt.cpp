// list_cad_faces with OCCT (cad_faces.hpp).
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>

#include "cnclab/cad/cad_faces.hpp"
#include "cnclab/cad/occt_nurbs.hpp"
#include "cnclab/cad/occt_shape_io.hpp"

namespace cnclab {

std::vector<CadFaceSummary> list_cad_faces(const std::filesystem::path& file) {
  const occt::CadShape shape = occt::read_cad_shape(file);
  std::vector<CadFaceSummary> out;
  for (std::size_t i = 0; i < shape.faces.size(); ++i) {
    const TopoDS_Face& f = shape.faces[i];
    CadFaceSummary s;
    s.index = static_cast<int>(i) + 1;
    s.surface_type = occt::surface_type_name(BRep_Tool::Surface(f));
    const occt::UvBounds b = occt::face_bounds(f);
    s.u0 = b.u0;
    s.u1 = b.u1;
    s.v0 = b.v0;
    s.v1 = b.v1;
    try {
      const Handle(Geom_BSplineSurface) nurbs = occt::face_nurbs(f, b);
      s.degree_u = nurbs->UDegree();
      s.degree_v = nurbs->VDegree();
    } catch (...) {
      // No NURBS form: degrees stay 0 (read_cad_surface says why).
    }
    GProp_GProps props;
    BRepGProp::SurfaceProperties(f, props);
    s.area = props.Mass();
    Bnd_Box box;
    BRepBndLib::AddOptimal(f, box, false, false);
    if (!box.IsVoid()) {
      double x0, y0, z0, x1, y1, z1;
      box.Get(x0, y0, z0, x1, y1, z1);
      s.box_min = {x0, y0, z0};
      s.box_max = {x1, y1, z1};
    }
    out.push_back(s);
  }
  return out;
}

}  // namespace cnclab
