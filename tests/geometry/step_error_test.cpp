#include "cnclab/geometry/step_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/geometry/surface_config.hpp"
#include "cnclab/geometry/tool_path.hpp"
#include "common/expect_error.hpp"
#include "geometry/shapes.hpp"

namespace cnclab {
namespace {

using testing::angle_xz;
using testing::kClosedFormTol;
using testing::kDeg;

struct CylinderCase {
  double rho, tool_radius;
  bool convex;
};

// A cylinder of radius rho about the y axis, machined from above: on the
// upper arc (30..150 deg) the tool is outside (convex), on the lower arc
// (210..330 deg) inside (concave). CC points theta apart on the circle give
// e = (rho + R)(1 - cos(theta/2)) outside, (rho - R)(1 - cos(theta/2)) inside
// (valid while e < R: a coarser step would put the CL line into the
// material). 41 points over 120 degrees: theta = 3 degrees.
void check_cylinder(const CylinderCase& c) {
  const NurbsSurface s = c.convex ? testing::cylinder(c.rho, 30 * kDeg, 150 * kDeg, 40.0)
                                  : testing::cylinder(c.rho, 210 * kDeg, 330 * kDeg, 40.0);
  ToolPathOptions o;
  o.lines = 3;
  o.points_per_line = 41;
  o.tool_radius = c.tool_radius;
  for (const ToolPathLine& path : plan_tool_path(s, o).lines) {
    for (std::size_t i = 0; i + 1 < path.t.size(); ++i) {
      const double expected_cl_radius = c.convex ? c.rho + c.tool_radius : c.rho - c.tool_radius;
      EXPECT_NEAR(std::hypot(path.cl[i].x(), path.cl[i].z()), expected_cl_radius, 1e-12);
      const double theta = std::abs(angle_xz(path.cc[i + 1]) - angle_xz(path.cc[i]));
      const double expected = expected_cl_radius * (1.0 - std::cos(theta / 2));
      const StepErrorSegment seg = path.segment(i);
      const StepError exact = exact_step_error(seg);
      EXPECT_NEAR(exact.error, expected, kClosedFormTol)
          << "rho " << c.rho << " R " << c.tool_radius << " segment " << i;
      EXPECT_EQ(exact.convex, c.convex);
      EXPECT_EQ(is_convex_segment(seg), c.convex);
      // p_e is the arc midpoint (symmetry).
      const double mid = 0.5 * (angle_xz(path.cc[i]) + angle_xz(path.cc[i + 1]));
      EXPECT_NEAR(angle_xz(curve_point(path.curve, exact.u_extreme)), mid, 1e-6);
      const StepError iterative = iterative_step_error(seg);
      EXPECT_NEAR(iterative.error, expected, kClosedFormTol);
    }
  }
}

TEST(StepError, ConvexCylinderClosedForm) {
  for (double rho : {3.0, 20.0, 150.0}) {
    for (double r : {0.5, 5.0, 12.0}) check_cylinder({rho, r, true});
  }
}

TEST(StepError, ConcaveCylinderClosedForm) {
  for (double rho : {20.0, 150.0}) {
    for (double r : {0.5, 5.0, 12.0}) check_cylinder({rho, r, false});
  }
}

NurbsSurface load_surface(const std::string& name) {
  const auto doc = ConfigDocument::load(CNCLAB_SOURCE_DIR "/configs/surfaces/" + name + ".yaml");
  NurbsSurface s = read_nurbs_surface(doc.root());
  doc.check_all_consumed();
  return s;
}

// Brute force: L on 10^5 + 1 equally spaced parameters per segment, the
// extreme the segment's classification asks for. The exact value must be at
// least as extreme and agree to the grid's resolution.
TEST(StepError, AgreesWithBruteForceScanOnTheTestSurfaces) {
  constexpr int kScan = 100'000;
  constexpr double kBruteForceTol = 1e-10;  // mm; the scan's own error is ~1e-12 mm
  Rng rng(2024);
  ToolPathOptions o;  // the paper's 200 x 100, R = 5 mm
  for (const char* name : {"surface1", "surface2", "surface3"}) {
    const NurbsSurface s = load_surface(name);
    const ToolPath planned = plan_tool_path(s, o);
    for (int trial = 0; trial < 4; ++trial) {
      const ToolPathLine& path = planned.lines[rng.below(o.lines)];
      for (int k = 0; k < 3; ++k) {
        const std::size_t i = rng.below(o.points_per_line - 1);
        const StepErrorSegment seg = path.segment(i);
        const StepError exact = exact_step_error(seg);
        const double sense = exact.convex ? 1.0 : -1.0;
        double best = sense * INFINITY;
        for (int j = 0; j <= kScan; ++j) {
          const double u = seg.u0 + (seg.u1 - seg.u0) * j / kScan;
          const double l = distance_to_cl_line(seg, u);
          if (sense * l < sense * best) best = l;
        }
        EXPECT_NEAR(exact.distance, best, kBruteForceTol) << name << " segment " << i;
        EXPECT_LE(sense * exact.distance, sense * best + 1e-13) << name;
        EXPECT_NEAR(exact.error, std::abs(o.tool_radius - best), kBruteForceTol) << name;
        const StepError iterative = iterative_step_error(seg);
        EXPECT_NEAR(iterative.error, exact.error, 1e-9) << name;
      }
    }
  }
}

std::string option_message(const ToolPathOptions& o) {
  return testing::error_message<OptionError>([&] { o.validate(); });
}

TEST(StepError, BadToolPathOptionsNameTheField) {
  ToolPathOptions o;
  o.tool_radius = 0.0;
  EXPECT_EQ(option_message(o), "tool_radius = 0: must be a finite ball radius > 0 mm");
  o.tool_radius = -2.0;
  EXPECT_NE(option_message(o).find("tool_radius = -2"), std::string::npos);
  o.tool_radius = NAN;
  EXPECT_NE(option_message(o).find("tool_radius"), std::string::npos);
  o = {};
  o.points_per_line = 1;
  EXPECT_NE(option_message(o).find("points_per_line = 1: must be in [2, 1000000]"),
            std::string::npos);
  o = {};
  o.lines = 1;
  EXPECT_NE(option_message(o).find("lines = 1"), std::string::npos);
  EXPECT_EQ(option_message({}), "no error");
}

TEST(StepError, CoincidentClPointsAreAnError) {
  const NurbsCurve c =
      testing::arc(10.0, 0.1, 1.0, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  const StepErrorSegment seg{&c, 0.0, 0.5, Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(1, 2, 3), 5.0};
  EXPECT_THROW(exact_step_error(seg), Error);
  ExactStepErrorOptions bad;
  bad.grid_intervals = 1;
  EXPECT_THROW(bad.validate(), OptionError);
  IterativeStepErrorOptions bad_iterative;
  bad_iterative.points_per_pass = 2;
  EXPECT_THROW(bad_iterative.validate(), OptionError);
}

}  // namespace
}  // namespace cnclab
