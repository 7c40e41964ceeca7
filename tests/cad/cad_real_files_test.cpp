// Real CAD files (tests/cad/data/README.md: origin and licence of each)
// through the step-error dataset path: every face agrees with OCCT's own
// evaluation or is refused naming face, line and reason; and the four cases
// a CAD user meets, each against its closed form or a dense evaluation of
// the face's own NURBS: a sphere through its poles, a cylinder whose path
// crosses vertical, a concave face with a too-large tool, a trimmed B-spline
// face with a hole.
#include <gtest/gtest.h>

#include <BRepAdaptor_Surface.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRep_Tool.hxx>
#include <Geom_BSplineSurface.hxx>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "cad/cad_corpus_check.hpp"
#include "cad/cad_fixtures.hpp"
#include "cnclab/cad/cad_export.hpp"
#include "cnclab/cad/cad_faces.hpp"
#include "cnclab/cad/occt_nurbs.hpp"
#include "cnclab/cad/occt_part.hpp"
#include "cnclab/data/step_error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

const fs::path kData = CNCLAB_SOURCE_DIR "/tests/cad/data";
using testing::kClosedFormTolUm;
using testing::kDeg;

// The dataset options of face `face` of `file` (K = 3), planned on construction.
StepErrorDatasetOptions face_options(const fs::path& file, int face, std::size_t lines,
                                     std::size_t points, double radius) {
  StepErrorDatasetOptions o;
  auto cad = std::make_shared<CadSurface>(read_cad_surface(file, face));
  o.surface = cad->surface;
  o.surface_name = cad->label();
  o.cad = cad;
  o.tool_path.lines = lines;
  o.tool_path.points_per_line = points;
  o.tool_path.tool_radius = radius;
  o.curve_points = 3;
  return o;
}

Dataset dataset(const StepErrorGenerator& g) {
  Rng unused(0);
  return g.generate(unused);
}

PathRefused refusal(const StepErrorDatasetOptions& o) {
  try {
    StepErrorGenerator g(o);
  } catch (const PathRefused& e) {
    return e;
  }
  ADD_FAILURE() << "no refusal";
  return PathRefused("", Refusal::nothing_left, 1);
}

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Inputs with K = 3: CC_i at 9..11, CC_i+1 at 12..14, CL_i at 15..17, CL_i+1 at 18..20.
Eigen::Vector3d input(const Dataset& d, Eigen::Index s, int first) {
  return d.inputs.col(s).segment<3>(first);
}

TEST(CadRealFiles, EveryFaceAgreesWithOcctOrIsRefusedWithFaceLineAndReason) {
  testing::CorpusOptions o;
  o.lines = o.points_per_line = 16;
  o.checked_samples = 12;
  std::size_t datasets = 0;
  for (const char* name :
       {"revolved_sphere.step", "sliced_cylinder.step", "red_cube_blue_cylinder.step", "screw.step",
        "hammer_face14.igs", "linkrods_face17.step"}) {
    const testing::FileCheck c = testing::check_cad_file(kData / name, o);
    ASSERT_EQ(c.read_error, "") << name;
    for (const auto* faces : {&c.refuse, &c.clip}) {
      for (const testing::FaceCheck& f : *faces) {
        EXPECT_EQ(f.disagreement, "") << name << " face " << f.face << ": " << f.message;
        if (f.outcome != "dataset") continue;
        ++datasets;
        EXPECT_LT(f.max_step_error_um, 1000 * o.tool_radius) << name << " face " << f.face;
      }
    }
  }
  EXPECT_GE(datasets, 10u);
}

// The sphere (radius 5 mm about the origin) as its own file writes it: u
// the longitude, v the latitude from pole to pole. Lines along v are great
// circles through both poles, whatever the density.
TEST(CadRealFiles, SphereThroughItsPolesAgainstTheClosedForm) {
  const fs::path file = kData / "revolved_sphere.step";
  const double rho = 5.0, radius = 2.0;
  for (const std::size_t density : {8u, 31u, 120u}) {
    StepErrorDatasetOptions o = face_options(file, 1, density, density + 1, radius);
    o.tool_path.feed = FeedDirection::v;
    const PathRefused e = refusal(o);
    EXPECT_EQ(e.reason(), Refusal::degenerate) << e.what();
    EXPECT_TRUE(has(e.what(), "face 1 of " + file.string() + ": line 0 (u = 0), CC point 0"))
        << e.what();
    EXPECT_TRUE(has(e.what(), "S_u x S_v vanishes there")) << e.what();
    o.tool_path.unreachable = UnreachablePolicy::clip;
    const StepErrorGenerator g(o);
    // Both ends of every meridian are poles: cut, never given a normal.
    EXPECT_EQ(g.path().cuts.degenerate, 2 * density);
    const Dataset d = dataset(g);
    ASSERT_GT(d.num_samples(), 0u);
    for (Eigen::Index s = 0; s < static_cast<Eigen::Index>(d.num_samples()); ++s) {
      const Eigen::Vector3d cc0 = input(d, s, 9), cc1 = input(d, s, 12);
      const Eigen::Vector3d cl0 = input(d, s, 15), cl1 = input(d, s, 18);
      EXPECT_NEAR(cc0.norm(), rho, 1e-9);
      // The outward normal is radial: CL = CC (rho + R) / rho, within 85 deg of +z.
      EXPECT_NEAR((cl0 - cc0 * (rho + radius) / rho).norm(), 0.0, 1e-9) << s;
      EXPECT_NEAR((cl1 - cc1 * (rho + radius) / rho).norm(), 0.0, 1e-9) << s;
      EXPECT_GE(cc0.z() / rho, std::cos(85 * kDeg) - 1e-12);
      // On a great circle: e = (rho + R)(1 - cos(theta / 2)).
      const double theta = std::acos(std::clamp(cc0.dot(cc1) / (rho * rho), -1.0, 1.0));
      EXPECT_NEAR(d.targets(0, s), 1000 * (rho + radius) * (1 - std::cos(theta / 2)),
                  kClosedFormTolUm)
          << "density " << density << " sample " << s;
    }
  }
}

// The blue cylinder (radius and axis read from the file by OCCT) machined
// along x: its path crosses "vertical" (the normal perpendicular to the
// tool axis) twice per circle.
TEST(CadRealFiles, CylinderWhosePathCrossesVerticalAgainstTheClosedForm) {
  const fs::path file = kData / "red_cube_blue_cylinder.step";
  const CadPart part = read_cad_part(file);
  int face = 0;
  for (int i = 1; i <= part.face_count() && !face; ++i) {
    if (part.face(i).surface_type == "cylinder") face = i;
  }
  ASSERT_GT(face, 0);
  const BRepAdaptor_Surface adaptor(occt::part_face(part, face));
  ASSERT_EQ(adaptor.GetType(), GeomAbs_Cylinder);
  const gp_Cylinder cylinder = adaptor.Cylinder();  // with the face's placement
  const double rho = cylinder.Radius(), radius = 1.5;
  const gp_Ax1 axis = cylinder.Axis();
  const Eigen::Vector3d origin(axis.Location().X(), axis.Location().Y(), axis.Location().Z());
  const Eigen::Vector3d along(axis.Direction().X(), axis.Direction().Y(), axis.Direction().Z());
  EXPECT_NEAR(rho, 5.0, 1e-9);  // 0.005 m in the file
  StepErrorDatasetOptions o = face_options(file, face, 6, 73, radius);
  o.tool_path.tool_axis = {1, 0, 0};
  const PathRefused e = refusal(o);
  EXPECT_EQ(e.reason(), Refusal::unreachable);
  EXPECT_TRUE(has(e.what(), "face " + std::to_string(face) + " of " + file.string() + ": line "))
      << e.what();
  EXPECT_TRUE(has(e.what(), "deg from the tool axis (1, 0, 0)")) << e.what();
  o.tool_path.unreachable = UnreachablePolicy::clip;
  const StepErrorGenerator g(o);
  const Dataset d = dataset(g);
  ASSERT_GT(d.num_samples(), 0u);
  EXPECT_GT(g.path().cuts.unreachable, 0u);
  const auto radial = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d r = p - origin - (p - origin).dot(along) * along;
    return r;
  };
  for (Eigen::Index s = 0; s < static_cast<Eigen::Index>(d.num_samples()); ++s) {
    const Eigen::Vector3d r0 = radial(input(d, s, 9)), r1 = radial(input(d, s, 12));
    EXPECT_NEAR(r0.norm(), rho, 1e-9);
    EXPECT_GE(r0.normalized().x(), std::cos(85 * kDeg) - 1e-12) << s;  // the reachable side
    EXPECT_NEAR((input(d, s, 15) - input(d, s, 9) - radius * r0.normalized()).norm(), 0, 1e-9);
    const double theta = std::acos(std::clamp(r0.dot(r1) / (rho * rho), -1.0, 1.0));
    EXPECT_NEAR(d.targets(0, s), 1000 * (rho + radius) * (1 - std::cos(theta / 2)),
                kClosedFormTolUm)
        << s;
  }
}

// A concave torus fillet of tube radius 0.125 mm: a 5 mm ball is refused
// naming the radii, kept and flagged with gouge: allow; a 0.1 mm ball fits
// and agrees with the dense evaluation of the face's NURBS.
TEST(CadRealFiles, ConcaveFaceWithATooLargeToolIsRefusedNamingTheRadii) {
  const fs::path file = kData / "linkrods_face17.step";
  StepErrorDatasetOptions o = face_options(file, 1, 12, 12, 5.0);
  const PathRefused e = refusal(o);
  EXPECT_EQ(e.reason(), Refusal::gouge);
  EXPECT_TRUE(has(e.what(), "face 1 of " + file.string() + ": line ")) << e.what();
  EXPECT_TRUE(has(e.what(),
                  "R = 5 mm exceeds the surface's smallest concave radius of "
                  "curvature 0.125 mm"))
      << e.what();
  o.tool_path.gouge = GougePolicy::allow;
  o.tool_path.unreachable = UnreachablePolicy::clip;
  const Dataset flagged = dataset(StepErrorGenerator(o));
  ASSERT_GT(flagged.num_samples(), 0u);
  EXPECT_EQ(flagged.metadata.row(flagged.metadata_row("gouge")).minCoeff(), 1.0);
  // OCCT's own curvature (surface show) names the same radius, concave.
  const CadFaceSummary summary = summarise_cad_part(file).faces.front();
  EXPECT_NEAR(summary.min_radius, 0.125, 1e-9);
  EXPECT_TRUE(summary.min_radius_concave);
  EXPECT_EQ(summary.usable, "gouge");
  testing::CorpusOptions fits;
  fits.tool_radius = 0.1;
  fits.lines = fits.points_per_line = 20;
  const testing::FaceCheck check = testing::check_cad_file(file, fits).clip.front();
  EXPECT_EQ(check.outcome, "dataset") << check.message;
  EXPECT_EQ(check.disagreement, "");
  EXPECT_GT(check.samples, 100u);
}

// Face 14 of the hammer: a flat B-spline face with a hole. Each pair of
// neighbouring CC points is a sample exactly when both and their middle lie
// on the face by OCCT's 3-D classifier; lines through the hole split.
TEST(CadRealFiles, TrimmedBSplineFaceWithAHoleSplitsItsLines) {
  const fs::path file = kData / "hammer_face14.igs";
  const CadPart part = read_cad_part(file);
  const CadSurface cad = part.face(1);
  EXPECT_EQ(cad.surface_type, "bspline");
  EXPECT_TRUE(cad.trimmed);
  EXPECT_EQ(cad.holes, 1);
  const std::size_t lines = 25, points = 30;
  const StepErrorGenerator g(face_options(file, 1, lines, points, 5.0));
  const Dataset d = dataset(g);
  const TopoDS_Face& face = occt::part_face(part, 1);
  const Handle(Geom_BSplineSurface) nurbs = occt::face_nurbs(face, occt::face_bounds(face));
  double u0, u1, v0, v1;
  nurbs->Bounds(u0, u1, v0, v1);
  const auto on_face = [&](double u, double v) {
    const TopAbs_State s = BRepClass_FaceClassifier(face, nurbs->Value(u, v), 1e-6).State();
    return s == TopAbs_IN || s == TopAbs_ON;
  };
  // The expected samples, line by line (lines at constant v, CC points
  // equally spaced in u: the path's definition, tool_path.hpp).
  std::size_t expected = 0, split_lines = 0;
  Eigen::Index s = 0;
  for (std::size_t l = 0; l < lines; ++l) {
    const double v = v0 + (v1 - v0) * static_cast<double>(l) / (lines - 1);
    std::size_t runs = 0;
    bool in_run = false;
    for (std::size_t k = 0; k + 1 < points; ++k) {
      const double ua = u0 + (u1 - u0) * static_cast<double>(k) / (points - 1);
      const double ub = u0 + (u1 - u0) * static_cast<double>(k + 1) / (points - 1);
      const bool sample = on_face(ua, v) && on_face(ub, v) && on_face(0.5 * (ua + ub), v);
      runs += sample && !in_run;
      in_run = sample;
      if (!sample) continue;
      ++expected;
      ASSERT_LT(s, static_cast<Eigen::Index>(d.num_samples()));
      EXPECT_EQ(d.metadata(0, s), static_cast<double>(l));
      EXPECT_EQ(d.metadata(1, s), static_cast<double>(runs - 1));  // the segment
      EXPECT_EQ(d.metadata(2, s), static_cast<double>(k));
      EXPECT_NEAR(d.targets(0, s), 0.0, 1e-6);  // a plane: L = R exactly
      ++s;
    }
    split_lines += runs > 1;
  }
  EXPECT_EQ(d.num_samples(), expected);
  EXPECT_GE(split_lines, 2u);
}

// The exported face reads back as the same face: the same dataset.
TEST(CadRealFiles, ExportedFaceReadsBackTheSame) {
  testing::TempDir dir;
  const fs::path file = kData / "hammer_face14.igs";
  const fs::path copy = dir.path() / "copy.step";
  testing::write_file(copy, cad_face_text(read_cad_part(file), 1, CadFormat::step));
  const Dataset a = dataset(StepErrorGenerator(face_options(file, 1, 20, 30, 5.0)));
  const Dataset b = dataset(StepErrorGenerator(face_options(copy, 1, 20, 30, 5.0)));
  ASSERT_EQ(a.num_samples(), b.num_samples());
  EXPECT_EQ(a.metadata, b.metadata);
  EXPECT_LE((a.inputs - b.inputs).cwiseAbs().maxCoeff(), 1e-9);
}

// A file in centimetres reads in mm: its cylinders' radii of curvature are
// their CYLINDRICAL_SURFACE radii (10.0000038403635 and 9.99997248963645 in
// the file) times 10.
TEST(CadRealFiles, UnitsAndWriterComeFromTheHeader) {
  const CadPartSummary s = summarise_cad_part(kData / "sliced_cylinder.step");
  EXPECT_EQ(s.unit, "centimetre");
  EXPECT_EQ(s.writer, "Rhino 8.14");
  std::vector<double> radii;
  for (const CadFaceSummary& f : s.faces) {
    if (f.surface_type == "cylinder") radii.push_back(f.min_radius);
  }
  std::sort(radii.begin(), radii.end());
  ASSERT_EQ(radii.size(), 2u);
  EXPECT_NEAR(radii[0], 99.9997248963645, 1e-9);
  EXPECT_NEAR(radii[1], 100.000038403635, 1e-9);
  EXPECT_EQ(summarise_cad_part(kData / "screw.step").writer, "EUCLID");
  EXPECT_EQ(read_cad_part(kData / "red_cube_blue_cylinder.step").unit, "metre");
}

}  // namespace
}  // namespace cnclab
