#include "cnclab/cad/occt_nurbs.hpp"

#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <GeomAdaptor_Surface.hxx>
#include <GeomConvert.hxx>
#include <Geom_RectangularTrimmedSurface.hxx>
#include <Precision.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <algorithm>
#include <cmath>
#include <vector>

namespace cnclab::occt {

namespace {

// Distinct knots and multiplicities of a flat knot vector (exact equality:
// our knot vectors repeat knots by value).
struct OcctKnots {
  std::vector<double> values;
  std::vector<int> mults;
};

OcctKnots occt_knots(const std::vector<double>& flat) {
  OcctKnots k;
  for (double t : flat) {
    if (!k.values.empty() && k.values.back() == t) {
      ++k.mults.back();
    } else {
      k.values.push_back(t);
      k.mults.push_back(1);
    }
  }
  return k;
}

TColStd_Array1OfReal real_array(const std::vector<double>& v) {
  TColStd_Array1OfReal a(1, static_cast<int>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a(static_cast<int>(i) + 1) = v[i];
  return a;
}

TColStd_Array1OfInteger int_array(const std::vector<int>& v) {
  TColStd_Array1OfInteger a(1, static_cast<int>(v.size()));
  for (std::size_t i = 0; i < v.size(); ++i) a(static_cast<int>(i) + 1) = v[i];
  return a;
}

Handle(Geom_Surface) untrimmed(Handle(Geom_Surface) s) {
  while (auto trim = Handle(Geom_RectangularTrimmedSurface)::DownCast(s)) s = trim->BasisSurface();
  return s;
}

bool near_bound(double a, double b, double range) {
  return std::abs(a - b) <= Precision::PConfusion() * std::max(1.0, std::abs(range));
}

}  // namespace

Handle(Geom_BSplineSurface) to_occt(const NurbsSurface& s) {
  s.validate();
  TColgp_Array2OfPnt poles(1, static_cast<int>(s.count_u), 1, static_cast<int>(s.count_v));
  TColStd_Array2OfReal weights(1, static_cast<int>(s.count_u), 1, static_cast<int>(s.count_v));
  for (std::size_t i = 0; i < s.count_u; ++i) {
    for (std::size_t j = 0; j < s.count_v; ++j) {
      const Eigen::Vector3d& p = s.point(i, j);
      poles(static_cast<int>(i) + 1, static_cast<int>(j) + 1) = gp_Pnt(p.x(), p.y(), p.z());
      weights(static_cast<int>(i) + 1, static_cast<int>(j) + 1) = s.weight(i, j);
    }
  }
  const OcctKnots ku = occt_knots(s.knots_u), kv = occt_knots(s.knots_v);
  return new Geom_BSplineSurface(poles, weights, real_array(ku.values), real_array(kv.values),
                                 int_array(ku.mults), int_array(kv.mults), s.degree_u, s.degree_v);
}

NurbsSurface from_occt(const Geom_BSplineSurface& in) {
  Handle(Geom_BSplineSurface) b = Handle(Geom_BSplineSurface)::DownCast(in.Copy());
  if (b->IsUPeriodic()) b->SetUNotPeriodic();
  if (b->IsVPeriodic()) b->SetVNotPeriodic();
  // Unclamped ends (first knot multiplicity <= degree) are clamped by
  // segmenting over the surface's own range (exact knot insertion).
  const auto clamped = [&] {
    return b->UMultiplicity(1) == b->UDegree() + 1 &&
           b->UMultiplicity(b->NbUKnots()) == b->UDegree() + 1 &&
           b->VMultiplicity(1) == b->VDegree() + 1 &&
           b->VMultiplicity(b->NbVKnots()) == b->VDegree() + 1;
  };
  if (!clamped()) {
    double u0, u1, v0, v1;
    b->Bounds(u0, u1, v0, v1);
    b->Segment(u0, u1, v0, v1);
  }
  NurbsSurface s;
  s.degree_u = b->UDegree();
  s.degree_v = b->VDegree();
  s.count_u = static_cast<std::size_t>(b->NbUPoles());
  s.count_v = static_cast<std::size_t>(b->NbVPoles());
  for (double t : b->UKnotSequence()) s.knots_u.push_back(t);
  for (double t : b->VKnotSequence()) s.knots_v.push_back(t);
  for (int i = 1; i <= b->NbUPoles(); ++i) {
    for (int j = 1; j <= b->NbVPoles(); ++j) {
      const gp_Pnt p = b->Pole(i, j);
      s.points.emplace_back(p.X(), p.Y(), p.Z());
      s.weights.push_back(b->Weight(i, j));
    }
  }
  return s;
}

UvBounds raw_face_bounds(const TopoDS_Face& face) {
  UvBounds b;
  BRepTools::UVBounds(face, b.u0, b.u1, b.v0, b.v1);
  return b;
}

namespace {

// [lo, hi] kept inside the surface's [first, last] in a bounded direction.
// In a periodic one: ends within rounding (1e-9 of the period) of a whole
// period snapped to it, and a span of a period plus or minus rounding made
// exactly one period: OCCT 7.6's GeomConvert fails on a cylinder over
// [-4e-13, 2 pi] (NCollection_Array2::Allocate), converts [0, 2 pi].
void clamp_range(double& lo, double& hi, double first, double last, bool periodic, double period) {
  if (periodic) {
    const double rounding = 1e-9 * period;
    const double whole = period * std::round(lo / period);
    if (std::abs(lo - whole) <= rounding) lo = whole;
    if (hi - lo >= period - rounding) hi = lo + period;
    return;
  }
  lo = std::max(lo, first);
  hi = std::min(hi, last);
}

}  // namespace

UvBounds face_bounds(const TopoDS_Face& face) {
  UvBounds b = raw_face_bounds(face);
  const Handle(Geom_Surface) base = untrimmed(BRep_Tool::Surface(face));
  if (base.IsNull()) return b;
  double u0, u1, v0, v1;
  base->Bounds(u0, u1, v0, v1);
  clamp_range(b.u0, b.u1, u0, u1, base->IsUPeriodic(), base->IsUPeriodic() ? base->UPeriod() : 0.0);
  clamp_range(b.v0, b.v1, v0, v1, base->IsVPeriodic(), base->IsVPeriodic() ? base->VPeriod() : 0.0);
  return b;
}

Handle(Geom_BSplineSurface) face_nurbs(const TopoDS_Face& face, const UvBounds& b) {
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(face);
  const Handle(Geom_Surface) base = untrimmed(surface);
  if (auto spline = Handle(Geom_BSplineSurface)::DownCast(base)) {
    double u0, u1, v0, v1;
    spline->Bounds(u0, u1, v0, v1);
    if (near_bound(b.u0, u0, u1 - u0) && near_bound(b.u1, u1, u1 - u0) &&
        near_bound(b.v0, v0, v1 - v0) && near_bound(b.v1, v1, v1 - v0)) {
      return spline;  // the whole surface: no knot insertion, no rounding
    }
  }
  return GeomConvert::SurfaceToBSplineSurface(
      new Geom_RectangularTrimmedSurface(base, b.u0, b.u1, b.v0, b.v1));
}

bool keeps_parameters(const Handle(Geom_Surface) & surface) {
  const std::string type = surface_type_name(surface);
  return type == "bspline" || type == "bezier" || type == "plane";
}

std::string surface_type_name(const Handle(Geom_Surface) & surface) {
  switch (GeomAdaptor_Surface(untrimmed(surface)).GetType()) {
    case GeomAbs_Plane:
      return "plane";
    case GeomAbs_Cylinder:
      return "cylinder";
    case GeomAbs_Cone:
      return "cone";
    case GeomAbs_Sphere:
      return "sphere";
    case GeomAbs_Torus:
      return "torus";
    case GeomAbs_BezierSurface:
      return "bezier";
    case GeomAbs_BSplineSurface:
      return "bspline";
    case GeomAbs_SurfaceOfRevolution:
      return "revolution";
    case GeomAbs_SurfaceOfExtrusion:
      return "extrusion";
    case GeomAbs_OffsetSurface:
      return "offset";
    case GeomAbs_OtherSurface:
      return "other";
  }
  return "other";
}

}  // namespace cnclab::occt
