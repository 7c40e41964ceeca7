#include "cad/cad_corpus_check.hpp"

#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRep_Tool.hxx>
#include <Eigen/Geometry>
#include <Geom_BSplineSurface.hxx>
#include <ShapeAnalysis_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "cnclab/cad/occt_nurbs.hpp"
#include "cnclab/cad/occt_part.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/step_error.hpp"

namespace cnclab::testing {
namespace {

constexpr std::size_t kCurvePoints = 3;  // K: CC_i at inputs 9..11, CC_i+1 12..14, CL 15..20
constexpr double kPointTolMm = 1e-8;     // our evaluation against OCCT's, + 1e-12 |p|
constexpr double kSurfaceTolMm = 1e-6;   // the NURBS form against the face's own surface
constexpr double kScanTolUm = 1e-5;      // the target against the dense scan, + 1e-9 of it
constexpr double kSolidStepMm = 1e-3;    // the step off the face for the solid classifier

Eigen::Vector3d eigen(const gp_Pnt& p) {
  return {p.X(), p.Y(), p.Z()};
}

gp_Pnt occt_point(const Eigen::Vector3d& p) {
  return {p.x(), p.y(), p.z()};
}

std::string text(const Eigen::Vector3d& p) {
  return std::string("(")
      .append(std::to_string(p.x()))
      .append(", ")
      .append(std::to_string(p.y()))
      .append(", ")
      .append(std::to_string(p.z()))
      .append(")");
}

// What was refused, from the message (PathRefused carries its reason).
std::string reason_of(const std::string& message) {
  if (message.find("no NURBS form") != std::string::npos) return "no NURBS form";
  if (message.find("has no surface") != std::string::npos) return "mesh face";
  if (message.find("is not below the tool radius") != std::string::npos) {
    return "step error not below R";
  }
  if (message.find("CL points coincide") != std::string::npos) return "CL points coincide";
  return "other";
}

// Where a refusal must point: the face always; the line unless no single
// line is to blame (nothing left, no NURBS form, no surface).
std::string refusal_disagreement(const FaceCheck& f, const std::string& label) {
  if (f.message.find(label) == std::string::npos) return "the refusal does not name " + label;
  const bool per_line = f.outcome != "nothing left on the face" && f.outcome != "no NURBS form" &&
                        f.outcome != "mesh face";
  if (per_line && f.message.find(": line ") == std::string::npos) {
    return "the refusal does not name the line";
  }
  if (f.outcome == "other") return "refused for an unexpected reason";
  return {};
}

struct SampleContext {
  const TopoDS_Face& face;
  const TopoDS_Shape& shape;
  const CadSurface& cad;
  const Geom_BSplineSurface& nurbs;  // OCCT's, evaluated by OCCT
  const CorpusOptions& options;
  Eigen::Vector3d axis;
  int side = 0;                 // the sign of the whole face's tool side, from the first sample
  Eigen::Index solid_from = 0;  // the first sample the solid check may use
  bool solid_checked = false;
};

// "" when sample s agrees, else what disagrees.
std::string check_sample(const Dataset& d, Eigen::Index s, SampleContext& c, FaceCheck& out) {
  const double radius = c.options.tool_radius;
  const auto x = d.inputs.col(s);
  const double uv[2][2] = {{d.metadata(3, s), d.metadata(4, s)},
                           {d.metadata(5, s), d.metadata(6, s)}};
  const bool convex = d.metadata(7, s) == 1.0;
  const std::string where = std::string("sample ")
                                .append(std::to_string(s))
                                .append(" (line ")
                                .append(std::to_string(static_cast<long>(d.metadata(0, s))))
                                .append(", point ")
                                .append(std::to_string(static_cast<long>(d.metadata(2, s))))
                                .append(")");
  const Handle(Geom_Surface) own = BRep_Tool::Surface(c.face);
  const double tolerance = std::max(10 * BRep_Tool::Tolerance(c.face), 1e-6);
  for (int end = 0; end < 2; ++end) {
    const Eigen::Vector3d cc = x.segment<3>(9 + 3 * end), cl = x.segment<3>(15 + 3 * end);
    gp_Pnt p;
    gp_Vec du, dv;
    c.nurbs.D1(uv[end][0], uv[end][1], p, du, dv);
    if ((eigen(p) - cc).norm() > kPointTolMm + 1e-12 * cc.norm()) {
      return where + ": CC point " + text(cc) + " is not OCCT's " + text(eigen(p));
    }
    ShapeAnalysis_Surface projection(own);
    projection.ValueOfUV(p, kSurfaceTolMm);
    if (!(projection.Gap() <= kSurfaceTolMm)) {
      return where + ": CC point " + text(cc) + " is " + std::to_string(projection.Gap()) +
             " mm off the face's own surface";
    }
    const TopAbs_State state = BRepClass_FaceClassifier(c.face, p, tolerance).State();
    if (state != TopAbs_IN && state != TopAbs_ON) {
      return where + ": CC point " + text(cc) + " lies outside the face (3-D classifier)";
    }
    const gp_Vec normal = du.Crossed(dv);
    if (normal.Magnitude() <= 0) return where + ": no normal at a kept CC point";
    const Eigen::Vector3d n = eigen(gp_Pnt(normal.Normalized().XYZ()));
    const int side = (cl - cc).dot(n) >= 0 ? 1 : -1;
    if (c.side == 0) c.side = side;
    if (side != c.side) return where + ": the tool side flips within the face";
    if ((cl - cc - radius * side * n).norm() > 1e-8 * radius) {
      return where + ": CL is not CC + R n";
    }
    if (side * n.dot(c.axis) < std::cos(85 * std::numbers::pi / 180) - 1e-12) {
      return where + ": the normal is beyond 85 deg from the tool axis";
    }
    // (A point strictly inside the face, from the middle of the dataset on:
    // from an edge, a step along the normal can leave the solid through
    // the neighbouring face.)
    if (c.cad.context.of_solid && !c.solid_checked && state == TopAbs_IN && s >= c.solid_from) {
      c.solid_checked = true;
      // Against the face's own solid (an assembly's parts may touch).
      for (TopExp_Explorer solid(c.shape, TopAbs_SOLID); solid.More(); solid.Next()) {
        bool owns = false;
        for (TopExp_Explorer f(solid.Current(), TopAbs_FACE); f.More() && !owns; f.Next()) {
          owns = f.Current().IsSame(c.face);
        }
        if (!owns) continue;
        const gp_Pnt off = occt_point(cc + kSolidStepMm * side * n);
        const gp_Pnt in = occt_point(cc - kSolidStepMm * side * n);
        if (BRepClass3d_SolidClassifier(solid.Current(), off, 1e-7).State() == TopAbs_IN ||
            BRepClass3d_SolidClassifier(solid.Current(), in, 1e-7).State() != TopAbs_IN) {
          return where + ": the tool is not on the solid's outside";
        }
        break;
      }
    }
  }
  // The dense scan of L along the CC curve between the two CC points, then
  // a second scan as dense over the two intervals around its extreme.
  const Eigen::Vector3d cl0 = x.segment<3>(15), axis = (x.segment<3>(18) - cl0).normalized();
  const auto distance = [&](double t) {
    const Eigen::Vector3d p = eigen(
        c.nurbs.Value(uv[0][0] + t * (uv[1][0] - uv[0][0]), uv[0][1] + t * (uv[1][1] - uv[0][1])));
    return (p - cl0).cross(axis).norm();
  };
  const int n = c.options.scan_intervals;
  double extreme = convex ? INFINITY : -INFINITY, best_t = 0;
  const auto scan = [&](double from, double to) {
    for (int k = 0; k <= n; ++k) {
      const double t = std::clamp(from + (to - from) * k / n, 0.0, 1.0);
      const double l = distance(t);
      if (convex ? l < extreme : l > extreme) {
        extreme = l;
        best_t = t;
      }
    }
  };
  scan(0, 1);
  scan(best_t - 1.0 / n, best_t + 1.0 / n);
  const double reference_um = 1000.0 * std::abs(radius - extreme);
  out.max_deviation_um = std::max(out.max_deviation_um, std::abs(d.targets(0, s) - reference_um));
  if (std::abs(d.targets(0, s) - reference_um) > kScanTolUm + 1e-9 * reference_um) {
    return where + ": step error " + std::to_string(d.targets(0, s)) + " um, the dense scan " +
           std::to_string(reference_um) + " um";
  }
  if (!(d.targets(0, s) < 1000.0 * radius)) return where + ": step error not below R";
  return {};
}

FaceCheck check_face(const CadPart& part, int index, UnreachablePolicy policy,
                     const CorpusOptions& o) {
  FaceCheck f;
  f.face = index;
  const TopoDS_Face& face = occt::part_face(part, index);
  const Handle(Geom_Surface) geom = BRep_Tool::Surface(face);
  f.type = geom.IsNull() ? "mesh" : occt::surface_type_name(geom);
  f.curved = f.type != "plane";
  const std::string label = "face " + std::to_string(index) + " of " + part.file_name;
  StepErrorDatasetOptions d;
  d.tool_path.lines = o.lines;
  d.tool_path.points_per_line = o.points_per_line;
  d.tool_path.tool_radius = o.tool_radius;
  d.tool_path.unreachable = policy;
  d.curve_points = kCurvePoints;
  Dataset dataset;
  try {
    auto cad = std::make_shared<CadSurface>(part.face(index));
    d.surface = cad->surface;
    d.surface_name = cad->label();
    d.cad = cad;
    const StepErrorGenerator generator(d);
    Rng unused(0);
    dataset = generator.generate(unused);
  } catch (const PathRefused& e) {
    f.outcome = refusal_name(e.reason());
    f.message = e.what();
  } catch (const ConfigError& e) {
    f.message = e.what();
    f.outcome = reason_of(f.message);
  }
  if (!f.message.empty()) {
    f.disagreement = refusal_disagreement(f, label);
    return f;
  }
  f.outcome = "dataset";
  f.samples = dataset.num_samples();
  f.max_step_error_um = dataset.targets.maxCoeff();
  const Handle(Geom_BSplineSurface) nurbs = occt::face_nurbs(face, occt::face_bounds(face));
  SampleContext context{face, part.shape->shape.shape,     *d.cad, *nurbs,
                        o,    d.tool_path.unit_tool_axis()};
  const auto n = static_cast<Eigen::Index>(f.samples);
  context.solid_from = n / 2;
  const auto checked =
      static_cast<Eigen::Index>(std::min<std::size_t>(f.samples, o.checked_samples));
  for (Eigen::Index k = 0; k < checked && f.disagreement.empty(); ++k) {
    const Eigen::Index s = checked == 1 ? 0 : k * (n - 1) / (checked - 1);
    f.disagreement = check_sample(dataset, s, context, f);
  }
  return f;
}

}  // namespace

FileCheck check_cad_file(const std::filesystem::path& file, const CorpusOptions& o) {
  FileCheck out;
  out.file = file.string();
  CadReadOptions read;
  read.read_timeout = o.read_timeout;
  CadPart part;
  try {
    part = read_cad_part(file, read);
  } catch (const ConfigError& e) {
    out.read_error = e.what();
    return out;
  }
  out.writer = part.writer;
  out.unit = part.unit;
  for (int i = 1; i <= part.face_count(); ++i) {
    out.refuse.push_back(check_face(part, i, UnreachablePolicy::refuse, o));
    out.clip.push_back(check_face(part, i, UnreachablePolicy::clip, o));
  }
  return out;
}

}  // namespace cnclab::testing
