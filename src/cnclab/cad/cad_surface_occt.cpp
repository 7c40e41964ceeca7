// read_cad_surface with OCCT (cad_surface.hpp).
#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Tool.hxx>
#include <GeomLib_Tool.hxx>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>

#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/cad/occt_nurbs.hpp"
#include "cnclab/cad/occt_shape_io.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"

namespace cnclab {
namespace {

// The face's wires as a 2-D classifier in the face's own parameters. Points
// of the NURBS form map to them unchanged where the conversion keeps the
// parametrisation, else through the 3-D point (GeomLib_Tool::Parameters:
// closed forms on quadrics, projection otherwise).
// t + k period for the integer k that puts it nearest the middle of [lo, hi].
double nearest_period(double t, double lo, double hi, double period) {
  return t + period * std::round((0.5 * (lo + hi) - t) / period);
}

class OcctFaceBoundary : public CadFaceBoundary {
 public:
  OcctFaceBoundary(const TopoDS_Face& face, const occt::UvBounds& bounds)
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
  std::ifstream in(file, std::ios::binary);
  if (!in) throw ConfigError(file.string() + ": cannot be opened for reading");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return hash_hex(bytes);
}

}  // namespace

CadSurface read_cad_surface(const std::filesystem::path& file, int face) {
  const occt::CadShape shape = occt::read_cad_shape(file);
  const int count = static_cast<int>(shape.faces.size());
  if (face < 1 || face > count) {
    throw ConfigError(file.string() + ": face " + std::to_string(face) +
                      " does not exist; the file has " + std::to_string(count) + " face" +
                      (count == 1 ? "" : "s") + " (1.." + std::to_string(count) +
                      "; `cnclab surface show " + file.string() + "` lists them)");
  }
  CadSurface out;
  out.file_name = file.string();
  out.file_hash = file_content_hash(file);
  out.face = face;
  const TopoDS_Face& f = shape.faces[static_cast<std::size_t>(face - 1)];
  try {
    out.surface_type = occt::surface_type_name(BRep_Tool::Surface(f));
    const occt::UvBounds bounds = occt::face_bounds(f);
    out.surface = occt::from_occt(*occt::face_nurbs(f, bounds));
    out.boundary = std::make_shared<OcctFaceBoundary>(f, bounds);
  } catch (...) {
    throw ConfigError(out.label() + ": its " + out.surface_type +
                      " surface has no NURBS form in OCCT (" + occt::occt_failure_text() + ")");
  }
  try {
    out.surface.validate();
  } catch (const OptionError& e) {
    throw ConfigError(out.label() + ": its NURBS form is not usable: " + e.what());
  }
  return out;
}

}  // namespace cnclab
