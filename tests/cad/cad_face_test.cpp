// CAD faces written by OCCT itself (not through our NURBS code): an analytic
// cylinder gives the closed-form step error, units convert to mm, and bad
// files, faces and trimmed faces are clear ConfigErrors (issue 19 item 4).
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
#endif

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kClosedFormTolUm = 1e-6;  // step error [µm] against the closed form

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
    ASSERT_EQ(d.metadata(5, s), c.convex ? 1.0 : 0.0) << "sample " << s;
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

// A disk's parameter rectangle is its bounding square: the tool path's
// corner points lie off the face.
TEST(CadFaceErrors, PathLeavingATrimmedFaceNamesTheFace) {
  TempDir dir;
  const gp_Circ circle(gp_Ax2(gp_Pnt(0, 0, 5), gp_Dir(0, 0, 1)), 10.0);
  const TopoDS_Wire wire = BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle).Edge()).Wire();
  write_step(BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 5), gp_Dir(0, 0, 1)), wire).Face(),
             dir / "disk.step");
  const std::string config = testing::step_error_config(testing::cad_face(dir / "disk.step"));
  const std::string message =
      testing::error_message<ConfigError>([&] { testing::step_error_generator(config); });
  EXPECT_NE(message.find("face 1 of " + (dir / "disk.step").string()), std::string::npos)
      << message;
  EXPECT_NE(message.find("(plane) is trimmed and the tool path leaves it"), std::string::npos)
      << message;
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
