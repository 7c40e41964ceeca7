// CAD faces written by OCCT itself (not through our NURBS code): an analytic
// cylinder gives the closed-form step error, units convert to mm, trims and
// whole periods clip and convert, and bad files and faces are clear
// ConfigErrors.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cad/cad_fixtures.hpp"
#include "cnclab/cad/cad_format.hpp"
#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

#ifdef CNCLAB_TEST_WITH_OCCT
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <STEPControl_Writer.hxx>
#include <StepData_StepModel.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Circ.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Pln.hxx>
#include <gp_Torus.hxx>
#endif

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

using testing::kClosedFormTolUm;
using testing::kDeg;

std::string read_error(const fs::path& file, int face) {
  return testing::error_message<ConfigError>([&] { read_cad_surface(file, face); });
}

#ifdef CNCLAB_TEST_WITH_OCCT

// OCCT's own STEP writer (default settings); `inch`: the file's length unit is
// the inch (header and values).
void write_step(const TopoDS_Shape& shape, const fs::path& file, bool inch = false) {
  STEPControl_Writer writer;  // (defines the write.step.* statics)
  if (inch) {
    // The header's unit (write.step.unit) and the values' scale (mm per file unit).
    ASSERT_TRUE(Interface_Static::SetCVal("write.step.unit", "INCH"));
    writer.Model()->SetWriteLengthUnit(25.4);
  }
  ASSERT_EQ(writer.Transfer(shape, STEPControl_AsIs), IFSelect_RetDone);
  ASSERT_EQ(writer.Write(file.c_str()), IFSelect_RetDone);
  if (inch) Interface_Static::SetCVal("write.step.unit", "MM");
}

// A cylinder face of radius rho about the y axis (u: the angle in the x-z
// plane, x = rho cos u, z = rho sin u; v along -y, 40 mm), between angles a0
// and a1: tool-path lines (constant v) are arcs in x-z planes, the paper's
// case, machined from +z: convex over 30..150 deg, concave over 210..330.
TopoDS_Face cylinder_face(double rho, double a0, double a1) {
  const gp_Cylinder c(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, -1, 0), gp_Dir(1, 0, 0)), rho);
  return BRepBuilderAPI_MakeFace(c, a0, a1, 0.0, 40.0).Face();
}

struct CylinderCase {
  double rho, tool_radius;
  bool convex;
};

// Sample by sample: e = (rho + R)(1 - cos(theta/2)) convex,
// (rho - R)(1 - cos(theta/2)) concave, theta the angle between the segment's
// CC points (tests/geometry/step_error_test.cpp has the derivation).
void expect_closed_form(const Dataset& d, const CylinderCase& c) {
  const auto k = static_cast<Eigen::Index>(3 * 3);  // K = 3: CC_i at inputs 9..11
  for (Eigen::Index s = 0; s < static_cast<Eigen::Index>(d.num_samples()); ++s) {
    const double a0 = std::atan2(d.inputs(k + 2, s), d.inputs(k, s));
    const double a1 = std::atan2(d.inputs(k + 5, s), d.inputs(k + 3, s));
    const double theta = std::abs(a1 - a0);
    const double cl_radius = c.convex ? c.rho + c.tool_radius : c.rho - c.tool_radius;
    const double expected_um = cl_radius * (1.0 - std::cos(theta / 2)) * 1000.0;
    ASSERT_NEAR(d.targets(0, s), expected_um, kClosedFormTolUm)
        << "rho " << c.rho << " R " << c.tool_radius << " sample " << s;
    ASSERT_EQ(d.metadata(d.metadata_row("convex"), s), c.convex ? 1.0 : 0.0) << "sample " << s;
  }
}

Dataset cylinder_dataset(const fs::path& file, const CylinderCase& c) {
  return testing::step_error_dataset(
      testing::step_error_config(testing::cad_face(file), 3, 25, c.tool_radius));
}

TEST(CadCylinderFace, GivesTheClosedFormStepError) {
  TempDir dir;
  for (const CylinderCase& c :
       {CylinderCase{20, 5, true}, CylinderCase{150, 12, true}, CylinderCase{3, 0.5, true},
        CylinderCase{20, 5, false}, CylinderCase{150, 12, false}}) {
    const fs::path file = dir / "cylinder.step";
    write_step(c.convex ? cylinder_face(c.rho, 30 * kDeg, 150 * kDeg)
                        : cylinder_face(c.rho, 210 * kDeg, 330 * kDeg),
               file);
    const CadSurface cad = read_cad_surface(file, 1);
    EXPECT_EQ(cad.surface_type, "cylinder");
    expect_closed_form(cylinder_dataset(file, c), c);
  }
}

// OCCT's own IGES writer in `unit` ("MM", "IN"), faces as trimmed surfaces.
void write_iges(const TopoDS_Shape& shape, const fs::path& file, const char* unit) {
  IGESControl_Writer writer(unit, 0);
  ASSERT_TRUE(writer.AddShape(shape));
  writer.ComputeModel();
  ASSERT_TRUE(writer.Write(file.c_str()));
}

// A file written in inches reads in mm: the same samples as the mm file.
TEST(CadCylinderFace, InchFileReadsInMillimetres) {
  TempDir dir;
  const CylinderCase c{20, 5, true};
  write_step(cylinder_face(c.rho, 30 * kDeg, 150 * kDeg), dir / "mm.step");
  write_step(cylinder_face(c.rho, 30 * kDeg, 150 * kDeg), dir / "inch.step", true);
  std::ifstream in(dir / "inch.step");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("INCH"), std::string::npos);
  EXPECT_NE(text.find("CYLINDRICAL_SURFACE('',#"), std::string::npos);
  EXPECT_NE(text.find("0.78740157480"), std::string::npos) << "radius 20 mm in inches";
  const Dataset mm = cylinder_dataset(dir / "mm.step", c);
  const Dataset inch = cylinder_dataset(dir / "inch.step", c);
  EXPECT_LE((mm.inputs - inch.inputs).cwiseAbs().maxCoeff(), 1e-9);
  expect_closed_form(inch, c);
  // IGES: the global section's unit flag (2HIN); OCCT writes the cylinder as
  // a surface of revolution, read back as one.
  write_iges(cylinder_face(c.rho, 30 * kDeg, 150 * kDeg), dir / "inch.igs", "IN");
  EXPECT_EQ(read_cad_surface(dir / "inch.igs", 1).surface_type, "revolution");
  // (Its NURBS parametrisation differs from the cylinder's: other CC points,
  // the same closed form.)
  expect_closed_form(cylinder_dataset(dir / "inch.igs", c), c);
}

// A disk's parameter rectangle is its bounding square: the path is clipped
// to the circle. A pair of neighbouring CC points is a sample exactly when
// both and their middle lie within the radius (closed form: the plane keeps
// its parameters, so the grid is a square grid on it).
TEST(CadTrims, DiskIsClippedToItsCircle) {
  TempDir dir;
  const double r = 10.0;
  const gp_Circ circle(gp_Ax2(gp_Pnt(0, 0, 5), gp_Dir(0, 0, 1)), r);
  const TopoDS_Wire wire = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire();
  write_step(BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 5), gp_Dir(0, 0, 1)), wire).Face(),
             dir / "disk.step");
  const CadSurface cad = read_cad_surface(dir / "disk.step", 1);
  EXPECT_TRUE(cad.trimmed);
  EXPECT_EQ(cad.holes, 0);
  const std::size_t lines = 9, points = 13;
  const Dataset d = testing::step_error_dataset(
      testing::step_error_config(testing::cad_face(dir / "disk.step"), lines, points));
  const auto inside = [&](double x, double y) { return std::hypot(x, y) <= r + 1e-9; };
  std::size_t expected = 0;
  Eigen::Index s = 0;
  for (std::size_t l = 0; l < lines; ++l) {
    const double y = -r + 2 * r * static_cast<double>(l) / (lines - 1);
    for (std::size_t k = 0; k + 1 < points; ++k) {
      const double xa = -r + 2 * r * static_cast<double>(k) / (points - 1);
      const double xb = -r + 2 * r * static_cast<double>(k + 1) / (points - 1);
      if (!(inside(xa, y) && inside(xb, y) && inside(0.5 * (xa + xb), y))) continue;
      ++expected;
      ASSERT_LT(s, static_cast<Eigen::Index>(d.num_samples()));
      EXPECT_NEAR(d.inputs(9, s), xa, 1e-9);  // CC_i
      EXPECT_NEAR(d.inputs(10, s), y, 1e-9);
      EXPECT_NEAR(d.targets(0, s), 0.0, 1e-9);  // a plane
      ++s;
    }
  }
  EXPECT_EQ(d.num_samples(), expected);
}

// A whole cylinder written over [-4e-13, 2 pi] (a period plus rounding, as
// CAD systems write them) converts, and its path, clipped to the reachable
// upper half, gives the closed form.
TEST(CadTrims, FullPeriodCylinderConvertsAndClipsToItsUpperHalf) {
  TempDir dir;
  const double rho = 20, radius = 5;
  const gp_Cylinder c(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, -1, 0), gp_Dir(1, 0, 0)), rho);
  write_step(BRepBuilderAPI_MakeFace(c, -4e-13, 2 * std::numbers::pi, 0.0, 40.0).Face(),
             dir / "tube.step");
  EXPECT_EQ(read_cad_surface(dir / "tube.step", 1).surface_type, "cylinder");
  const std::string config =
      testing::step_error_config(testing::cad_face(dir / "tube.step"), 3, 60) +
      "    unreachable: clip\n";
  const Dataset d = testing::step_error_dataset(config);
  ASSERT_GT(d.num_samples(), 0u);
  for (Eigen::Index s = 0; s < static_cast<Eigen::Index>(d.num_samples()); ++s) {
    const double a0 = std::atan2(d.inputs(11, s), d.inputs(9, s));
    const double a1 = std::atan2(d.inputs(14, s), d.inputs(12, s));
    EXPECT_GE(a0, 5 * kDeg - 1e-9);  // reachable: the normal within 85 deg of +z
    EXPECT_LE(a0, 175 * kDeg + 1e-9);
    EXPECT_NEAR(d.targets(0, s), (rho + radius) * (1 - std::cos((a1 - a0) / 2)) * 1000.0,
                kClosedFormTolUm);
  }
}

// A whole torus (both directions periodic) converts, and its NURBS form is
// the torus: every point lies the tube radius away from the circle of
// radius 30 in the x-y plane.
TEST(CadTrims, WholeTorusConverts) {
  TempDir dir;
  const double major = 30, minor = 8;
  const gp_Torus torus(gp_Ax3(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1), gp_Dir(1, 0, 0)), major, minor);
  write_step(
      BRepBuilderAPI_MakeFace(torus, 0, 2 * std::numbers::pi, 0, 2 * std::numbers::pi).Face(),
      dir / "torus.step");
  const CadSurface cad = read_cad_surface(dir / "torus.step", 1);
  EXPECT_EQ(cad.surface_type, "torus");
  EXPECT_FALSE(cad.trimmed);
  for (int i = 0; i <= 10; ++i) {
    for (int j = 0; j <= 10; ++j) {
      const double u = cad.surface.knots_u.front() +
                       (cad.surface.knots_u.back() - cad.surface.knots_u.front()) * i / 10.0;
      const double v = cad.surface.knots_v.front() +
                       (cad.surface.knots_v.back() - cad.surface.knots_v.front()) * j / 10.0;
      const Eigen::Vector3d p = surface_point(cad.surface, u, v);
      EXPECT_NEAR(std::hypot(std::hypot(p.x(), p.y()) - major, p.z()), minor, 1e-9);
    }
  }
}

// OCCT 7.6 keeps AP242's tessellated entities untranslated: a file holding
// only a mesh says so (a minimal AP242 file: one TRIANGULATED_FACE, ISO
// 10303-42, written here by hand).
TEST(CadFaceErrors, MeshOnlyFileSaysSo) {
  TempDir dir;
  testing::write_file(dir / "mesh.step", R"(ISO-10303-21;
HEADER;
FILE_DESCRIPTION((''),'2;1');
FILE_NAME('mesh','2024-01-01T00:00:00',(''),(''),'','','');
FILE_SCHEMA(('AP242_MANAGED_MODEL_BASED_3D_ENGINEERING_MIM_LF { 1 0 10303 442 1 1 4 }'));
ENDSEC;
DATA;
#1=APPLICATION_CONTEXT('managed model based 3d engineering');
#2=PRODUCT_CONTEXT('',#1,'mechanical');
#3=PRODUCT('mesh','mesh','',(#2));
#4=PRODUCT_DEFINITION_CONTEXT('part definition',#1,'design');
#5=PRODUCT_DEFINITION_FORMATION('','',#3);
#6=PRODUCT_DEFINITION('design','',#5,#4);
#7=PRODUCT_DEFINITION_SHAPE('','',#6);
#8=(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.));
#9=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));
#10=(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT());
#11=(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNIT_ASSIGNED_CONTEXT((#8,#9,#10))REPRESENTATION_CONTEXT('',''));
#12=COORDINATES_LIST('',4,((0.,0.,0.),(10.,0.,0.),(10.,10.,0.),(0.,10.,0.)));
#13=TRIANGULATED_FACE('',#12,4,((0.,0.,1.)),$,(1,2,3,4),((1,2,3),(1,3,4)));
#14=TESSELLATED_SHAPE_REPRESENTATION('',(#13),#11);
#15=SHAPE_DEFINITION_REPRESENTATION(#7,#14);
ENDSEC;
END-ISO-10303-21;
)");
  const std::string m = read_error(dir / "mesh.step", 1);
  EXPECT_NE(m.find("holds only a mesh"), std::string::npos) << m;
  EXPECT_NE(m.find("TRIANGULATED_FACE"), std::string::npos) << m;
}

// A read that takes longer than read_timeout stops with that, naming the option.
TEST(CadFaceErrors, ReadTimeoutNamesTheOption) {
  TempDir dir;
  write_step(cylinder_face(20, 30 * kDeg, 150 * kDeg), dir / "one.step");
  CadReadOptions o;
  o.read_timeout = 0.001;  // the fork and OCCT's start alone take longer
  const std::string m =
      testing::error_message<ConfigError>([&] { read_cad_surface(dir / "one.step", 1, o); });
  EXPECT_NE(m.find("one.step: timed out after 0.001 s reading it"), std::string::npos) << m;
  EXPECT_NE(m.find("read_timeout"), std::string::npos) << m;
  o.read_timeout = 0.0001;
  EXPECT_NE(testing::error_message<OptionError>([&] {
              o.validate();
            }).find("read_timeout = 0.0001: must be 0 (by the file's size) or seconds"),
            std::string::npos);
  EXPECT_EQ(default_read_timeout(0), 60.0);
  EXPECT_EQ(default_read_timeout(50'000'000), 560.0);
}

TEST(CadFaceErrors, FileWithoutFacesAndFaceOutOfRange) {
  TempDir dir;
  write_step(BRepBuilderAPI_MakeEdge(gp_Pnt(0, 0, 0), gp_Pnt(10, 0, 0)).Edge(), dir / "edge.step");
  EXPECT_NE(read_error(dir / "edge.step", 1).find("holds no face"), std::string::npos)
      << read_error(dir / "edge.step", 1);
  write_step(cylinder_face(20, 30 * kDeg, 150 * kDeg), dir / "one.step");
  EXPECT_NE(read_error(dir / "one.step", 2).find("face 2 does not exist; the file has 1 face"),
            std::string::npos)
      << read_error(dir / "one.step", 2);
  EXPECT_NE(read_error(dir / "one.step", 0).find("face 0 does not exist"), std::string::npos);
}

TEST(CadFaceErrors, TruncatedAndNonCadFiles) {
  TempDir dir;
  write_step(cylinder_face(20, 30 * kDeg, 150 * kDeg), dir / "one.step");
  std::ifstream in(dir / "one.step");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  testing::write_file(dir / "half.step", text.substr(0, text.size() / 2));
  EXPECT_NE(read_error(dir / "half.step", 1).find("half.step: "), std::string::npos);
  testing::write_file(dir / "text.step", "degree_u: 3\n");
  EXPECT_NE(read_error(dir / "text.step", 1).find("not a readable STEP file"), std::string::npos)
      << read_error(dir / "text.step", 1);
  testing::write_file(dir / "text.igs", "degree_u: 3\n");
  EXPECT_NE(read_error(dir / "text.igs", 1).find("text.igs: "), std::string::npos);
}

#endif  // CNCLAB_TEST_WITH_OCCT

TEST(CadFaceErrors, MissingFileAndUnknownExtension) {
  TempDir dir;
  testing::write_file(dir / "part.txt", "x");
  EXPECT_NE(read_error(dir / "part.txt", 1).find("not a CAD file name"), std::string::npos)
      << read_error(dir / "part.txt", 1);
  if (!cad_support_available()) {
    EXPECT_NE(read_error(dir / "part.step", 1).find("libocct-data-exchange-dev"),
              std::string::npos);
    return;
  }
  EXPECT_NE(read_error(dir / "missing.step", 1).find("missing.step: no such file"),
            std::string::npos)
      << read_error(dir / "missing.step", 1);
}

}  // namespace
}  // namespace cnclab
