// read_cad_part and CadPart with OCCT (cad_surface.hpp).
#include <BRepTools.hxx>
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <GeomLib_Tool.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Wire.hxx>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <iterator>

#include "cnclab/cad/occt_nurbs.hpp"
#include "cnclab/cad/occt_part.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"

namespace cnclab {
namespace {

// t + k period for the integer k that puts it nearest the middle of [lo, hi].
double nearest_period(double t, double lo, double hi, double period) {
  return t + period * std::round((0.5 * (lo + hi) - t) / period);
}

// The face's trimming loops (outer boundary and holes) as OCCT's 2-D face
// classifier in the face's own parameters. Points of the NURBS form map to
// them unchanged where the conversion keeps the parametrisation, else
// through the 3-D point (GeomLib_Tool::Parameters: closed forms on quadrics,
// projection otherwise).
class OcctFaceDomain : public FaceDomain {
 public:
  OcctFaceDomain(const TopoDS_Face& face, const occt::UvBounds& bounds)
      : face_(face),
        surface_(BRep_Tool::Surface(face)),
        same_parameters_(occt::keeps_parameters(surface_)),
        tolerance_(BRep_Tool::Tolerance(face)),
        bounds_(bounds),
        classifier_(face, 1e-9) {}

  bool contains(const NurbsSurface& surface, double u, double v) const override {
    if (!same_parameters_) {
      const Eigen::Vector3d point = surface_point(surface, u, v);
      // 10x the face tolerance: the NURBS form is exact, rounding aside.
      if (!GeomLib_Tool::Parameters(surface_, gp_Pnt(point.x(), point.y(), point.z()),
                                    10.0 * tolerance_ + 1e-7, u, v)) {
        return false;
      }
      // Parameters come back in the first period ([0, 2 pi) on quadrics);
      // the face may lie across it (u in [-pi/6, pi/6]).
      if (surface_->IsUPeriodic())
        u = nearest_period(u, bounds_.u0, bounds_.u1, surface_->UPeriod());
      if (surface_->IsVPeriodic())
        v = nearest_period(v, bounds_.v0, bounds_.v1, surface_->VPeriod());
    }
    const TopAbs_State state = classifier_.Perform(gp_Pnt2d(u, v));
    return state == TopAbs_IN || state == TopAbs_ON;
  }

 private:
  TopoDS_Face face_;  // keeps the classifier's edges alive
  Handle(Geom_Surface) surface_;
  bool same_parameters_;
  double tolerance_;
  occt::UvBounds bounds_;
  BRepTopAdaptor_FClass2d classifier_;
};

std::string file_content_hash(const std::filesystem::path& file) {
  std::optional<std::string> hash = file_hash_hex(file);
  if (!hash) throw ConfigError(file.string() + ": cannot be opened for reading");
  return *hash;
}

// Whether every edge of the outer loop runs along a side of the face's
// parameter box (or is degenerate, a pole): then the face is its parameter
// rectangle, not trimmed. Checked at each pcurve's ends and middle.
bool bounded_by_rectangle(const TopoDS_Face& face) {
  const occt::UvBounds b = occt::raw_face_bounds(face);
  const double tol_u = 1e-7 * std::max(1.0, b.u1 - b.u0), tol_v = 1e-7 * std::max(1.0, b.v1 - b.v0);
  const TopoDS_Wire outer = BRepTools::OuterWire(face);
  if (outer.IsNull()) return false;
  for (TopExp_Explorer e(outer, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (BRep_Tool::Degenerated(edge)) continue;
    double first = 0, last = 0;
    const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, first, last);
    if (pcurve.IsNull()) return false;
    const gp_Pnt2d p[] = {pcurve->Value(first), pcurve->Value(0.5 * (first + last)),
                          pcurve->Value(last)};
    const auto all = [&](auto on_side) { return on_side(p[0]) && on_side(p[1]) && on_side(p[2]); };
    if (!all([&](const gp_Pnt2d& q) { return std::abs(q.X() - b.u0) <= tol_u; }) &&
        !all([&](const gp_Pnt2d& q) { return std::abs(q.X() - b.u1) <= tol_u; }) &&
        !all([&](const gp_Pnt2d& q) { return std::abs(q.Y() - b.v0) <= tol_v; }) &&
        !all([&](const gp_Pnt2d& q) { return std::abs(q.Y() - b.v1) <= tol_v; })) {
      return false;
    }
  }
  return true;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

namespace occt {

const TopoDS_Face& part_face(const CadPart& part, int face) {
  const int count = part.face_count();
  if (face < 1 || face > count) {
    throw ConfigError(part.file_name + ": face " + std::to_string(face) +
                      " does not exist; the file has " + std::to_string(count) + " face" +
                      (count == 1 ? "" : "s") + " (1.." + std::to_string(count) +
                      "; `cnclab surface show " + part.file_name + "` lists them)");
  }
  return part.shape->shape.faces[static_cast<std::size_t>(face - 1)];
}

}  // namespace occt

CadPart read_cad_part(const std::filesystem::path& file, const CadReadOptions& options) {
  options.validate();
  std::error_code ec;
  const std::uintmax_t bytes = std::filesystem::file_size(file, ec);
  const double timeout =
      options.read_timeout > 0 ? options.read_timeout : default_read_timeout(ec ? 0 : bytes);
  auto data = std::make_shared<CadShapeData>();
  data->shape = occt::read_cad_shape(file, timeout);
  // Faces of closed shells of solids, in the orientation the solid gives them.
  TopTools_IndexedMapOfShape faces;
  for (const TopoDS_Face& f : data->shape.faces) faces.Add(f);
  data->of_solid.assign(data->shape.faces.size(), 0);
  for (TopExp_Explorer solid(data->shape.shape, TopAbs_SOLID); solid.More(); solid.Next()) {
    for (TopExp_Explorer shell(solid.Current(), TopAbs_SHELL); shell.More(); shell.Next()) {
      if (!BRep_Tool::IsClosed(shell.Current())) continue;
      for (TopExp_Explorer f(shell.Current(), TopAbs_FACE); f.More(); f.Next()) {
        const int index = faces.FindIndex(f.Current());
        if (index > 0) data->of_solid[static_cast<std::size_t>(index - 1)] = 1;
      }
    }
  }
  CadPart part;
  part.file_name = file.string();
  part.file_hash = file_content_hash(file);
  part.unit = lower(data->shape.unit);
  part.writer = data->shape.writer;
  part.shape = std::move(data);
  return part;
}

int CadPart::face_count() const {
  return shape ? static_cast<int>(shape->shape.faces.size()) : 0;
}

CadSurface CadPart::face(int face) const {
  const TopoDS_Face& f = occt::part_face(*this, face);
  CadSurface out;
  out.file_name = file_name;
  out.file_hash = file_hash;
  out.face = face;
  out.context.label = out.label();
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(f);
  if (surface.IsNull()) {
    throw ConfigError(out.label() + ": has no surface (a mesh face), so no tool path");
  }
  out.surface_type = occt::surface_type_name(surface);
  try {
    const occt::UvBounds bounds = occt::face_bounds(f);
    out.surface = occt::from_occt(*occt::face_nurbs(f, bounds));
    out.context.domain = std::make_shared<OcctFaceDomain>(f, bounds);
  } catch (...) {
    throw ConfigError(out.label() + ": its " + out.surface_type +
                      " surface has no NURBS form in OCCT (" + occt::occt_failure_text() + ")");
  }
  try {
    out.surface.validate();
  } catch (const OptionError& e) {
    throw ConfigError(out.label() + ": its NURBS form is not usable: " + e.what());
  }
  out.context.orientation = f.Orientation() == TopAbs_REVERSED ? -1 : 1;
  out.context.of_solid = shape->of_solid[static_cast<std::size_t>(face - 1)] != 0;
  int wires = 0;
  for (TopExp_Explorer w(f, TopAbs_WIRE); w.More(); w.Next()) ++wires;
  out.holes = std::max(0, wires - 1);
  out.trimmed = out.holes > 0 || !bounded_by_rectangle(f);
  return out;
}

}  // namespace cnclab
