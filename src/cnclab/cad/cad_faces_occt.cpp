// summarise_cad_part with OCCT (cad_faces.hpp).
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepLProp_SLProps.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <cmath>
#include <limits>

#include "cnclab/cad/cad_faces.hpp"
#include "cnclab/cad/occt_nurbs.hpp"
#include "cnclab/cad/occt_part.hpp"

namespace cnclab {
namespace {

constexpr int kGrid = 25;  // points per parameter direction of the normal/curvature survey

// The normal (times `side`: the tool's side of the face's surface normal)
// along the axis and the smallest radius of curvature over the grid points
// on the face, from OCCT's local properties of the face's own surface.
void survey(const TopoDS_Face& face, int side, const Eigen::Vector3d& axis, CadFaceSummary& s) {
  const BRepAdaptor_Surface surface(face, false);
  BRepTopAdaptor_FClass2d classifier(face, 1e-9);
  const occt::UvBounds b = occt::face_bounds(face);
  s.axis_min = INFINITY;
  s.axis_max = -INFINITY;
  double largest_curvature = 0;  // |kappa|, signed toward the tool below
  double signed_curvature = 0;
  for (int i = 0; i < kGrid; ++i) {
    for (int j = 0; j < kGrid; ++j) {
      const double u = b.u0 + (b.u1 - b.u0) * (i + 0.5) / kGrid;
      const double v = b.v0 + (b.v1 - b.v0) * (j + 0.5) / kGrid;
      if (classifier.Perform(gp_Pnt2d(u, v)) == TopAbs_OUT) continue;
      BRepLProp_SLProps props(surface, u, v, 2, 1e-9);
      if (!props.IsNormalDefined()) continue;
      const gp_Dir n = props.Normal();
      const double along = side * (n.X() * axis.x() + n.Y() * axis.y() + n.Z() * axis.z());
      s.axis_min = std::min(s.axis_min, along);
      s.axis_max = std::max(s.axis_max, along);
      if (!props.IsCurvatureDefined()) continue;
      // OCCT's curvatures are signed toward props.Normal(): positive where
      // the surface bends toward it.
      for (double k : {props.MaxCurvature(), props.MinCurvature()}) {
        if (std::abs(k) > largest_curvature) {
          largest_curvature = std::abs(k);
          signed_curvature = side * k;
        }
      }
    }
  }
  if (s.axis_min > s.axis_max) s.axis_min = s.axis_max = NAN;  // no grid point on the face
  s.min_radius = largest_curvature > 0 ? 1.0 / largest_curvature : INFINITY;
  s.min_radius_concave = signed_curvature > 0;
}

// The share of the grid's CC points on a segment of `path`.
double path_share(const ToolPath& path) {
  std::size_t on = 0;
  for (const ToolPathLine& line : path.lines) {
    for (const PathRun& run : line.runs) on += run.last - run.first + 1;
  }
  return static_cast<double>(on) / static_cast<double>(path.points());
}

}  // namespace

CadPartSummary summarise_cad_part(const std::filesystem::path& file,
                                  const CadShowOptions& options) {
  options.path.validate();
  const CadPart part = read_cad_part(file, options.read);
  const Eigen::Vector3d axis = options.path.unit_tool_axis();
  ToolPathOptions clip = options.path;
  clip.unreachable = UnreachablePolicy::clip;
  CadPartSummary out;
  out.unit = part.unit;
  out.writer = part.writer;
  for (int i = 1; i <= part.face_count(); ++i) {
    const TopoDS_Face& f = occt::part_face(part, i);
    CadFaceSummary s;
    s.index = i;
    const Handle(Geom_Surface) geom = BRep_Tool::Surface(f);
    s.surface_type = geom.IsNull() ? "mesh" : occt::surface_type_name(geom);
    const occt::UvBounds b = occt::face_bounds(f);
    s.u0 = b.u0;
    s.u1 = b.u1;
    s.v0 = b.v0;
    s.v1 = b.v1;
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
    // The tool side relative to OCCT's surface normal: the face's own
    // normal until a plan decides it (S_u x S_v of the NURBS form runs the
    // same way as the surface's, the conversion keeping its directions).
    int side = f.Orientation() == TopAbs_REVERSED ? -1 : 1;
    const auto verdict = [&](const CadSurface& cad, const ToolPathOptions& o, std::string& usable,
                             std::string* why) {
      try {
        const ToolPath path = plan_tool_path(cad.surface, o, cad.context);
        usable = "yes";
        side = path.side;
        return path_share(path);
      } catch (const PathRefused& e) {
        usable = refusal_name(e.reason());
        side = e.side();
        if (why) *why = e.what();
        return -1.0;
      }
    };
    try {
      const CadSurface cad = part.face(i);
      s.degree_u = cad.surface.degree_u;
      s.degree_v = cad.surface.degree_v;
      s.trimmed = cad.trimmed;
      s.holes = cad.holes;
      s.of_solid = cad.context.of_solid;
      s.clip_share = verdict(cad, clip, s.clip_usable, nullptr);
      verdict(cad, options.path, s.usable, &s.reason_text);
    } catch (const ConfigError& e) {  // no NURBS form, no surface
      s.usable = s.clip_usable = geom.IsNull() ? "mesh face" : "no NURBS form";
      s.reason_text = e.what();
    }
    if (!geom.IsNull()) survey(f, side, axis, s);
    out.faces.push_back(s);
  }
  return out;
}

}  // namespace cnclab
