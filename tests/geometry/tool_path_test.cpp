// Tool paths cut where a face cannot be machined (geometry/tool_path.hpp),
// against closed forms: a cylinder whose path crosses vertical, a sphere
// through its pole, a concave face with a too-large tool, trims with a hole.
#include "cnclab/geometry/tool_path.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/geometry/surface_curvature.hpp"
#include "common/expect_error.hpp"
#include "geometry/shapes.hpp"

namespace cnclab {
namespace {

using testing::angle_xz;
using testing::kClosedFormTol;
using testing::kDeg;

PathRefused refusal(const NurbsSurface& s, const ToolPathOptions& o, const FaceContext& f = {}) {
  try {
    plan_tool_path(s, o, f);
  } catch (const PathRefused& e) {
    return e;
  }
  ADD_FAILURE() << "no refusal";
  return PathRefused("", Refusal::nothing_left, 1);
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// A cylinder (radius 20 about the y axis) from -40 to 100 deg: below 0 deg
// its outside faces down, so a path across it from +z crosses vertical.
TEST(ToolPathReach, CylinderCrossingVerticalIsRefusedOrClippedToItsReachablePart) {
  const double rho = 20, radius = 5;
  const NurbsSurface s = testing::cylinder(rho, -40 * kDeg, 100 * kDeg, 30.0);
  ToolPathOptions o;
  o.lines = 4;
  o.points_per_line = 50;  // no CC point exactly at the 5 deg limit
  o.tool_radius = radius;
  const PathRefused e = refusal(s, o, {"the test cylinder", nullptr, 1, false});
  EXPECT_EQ(e.reason(), Refusal::unreachable);
  EXPECT_TRUE(contains(e.what(), "the test cylinder: line 0 (v = 0), CC point 0 at")) << e.what();
  EXPECT_TRUE(contains(e.what(), "130 deg from the tool axis (0, 0, 1)")) << e.what();
  EXPECT_TRUE(contains(e.what(), "unreachable: clip")) << e.what();

  o.unreachable = UnreachablePolicy::clip;
  const ToolPath path = plan_tool_path(s, o);
  EXPECT_EQ(path.side, -1);  // the outside faces +z; S_u x S_v of this arc points in
  std::size_t samples = 0;
  for (const ToolPathLine& line : path.lines) {
    ASSERT_EQ(line.runs.size(), 1u);
    for (std::size_t k = 0; k < line.t.size(); ++k) {
      const double angle = angle_xz(line.cc[k]);
      // The normal of the outside is radial, sin(angle) along z: reachable
      // from 5 deg (max_normal_angle 85) up.
      const bool reachable = angle >= 5 * kDeg - 1e-12;
      EXPECT_EQ(line.state[k] == PointState::on_path, reachable) << k;
      if (!reachable) continue;
      const Eigen::Vector3d radial(std::cos(angle), 0, std::sin(angle));
      EXPECT_NEAR((line.normal[k] - radial).norm(), 0.0, 1e-12);
    }
    const PathRun run = line.runs.front();
    for (std::size_t i = run.first; i < run.last; ++i) {
      const double theta = angle_xz(line.cc[i + 1]) - angle_xz(line.cc[i]);
      const double expected = (rho + radius) * (1 - std::cos(theta / 2));
      EXPECT_NEAR(exact_step_error(line.segment(i)).error, expected, kClosedFormTol);
      ++samples;
    }
  }
  EXPECT_EQ(samples, path.samples.size());
  EXPECT_EQ(path.cuts.unreachable + path.cuts.degenerate + path.cuts.outside_face,
            path.points() - samples - path.lines.size());
}

// A sphere patch from latitude 10 deg to the north pole (radius 25): S_v
// vanishes on the pole row. Whatever the path's density, the pole points
// are refused or cut, never given a normal, and every other normal is radial.
TEST(ToolPathPoles, SpherePoleIsRefusedOrClippedAtAnyDensity) {
  const double rho = 25;
  const NurbsCurve meridian =
      testing::arc(rho, 10 * kDeg, 90 * kDeg, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitZ());
  const NurbsCurve quarter =
      testing::arc(1, 0, std::numbers::pi / 2, Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY());
  NurbsSurface s;  // u along the meridian (pole at u = 1), v along the longitude
  s.degree_u = s.degree_v = 2;
  s.knots_u = s.knots_v = {0, 0, 0, 1, 1, 1};
  s.count_u = s.count_v = 3;
  for (std::size_t i = 0; i < 3; ++i) {
    for (std::size_t j = 0; j < 3; ++j) {
      const double r = meridian.points[i].x(), z = meridian.points[i].z();
      s.points.emplace_back(r * quarter.points[j].x(), r * quarter.points[j].y(), z);
      s.weights.push_back(meridian.weights[i] * quarter.weights[j]);
    }
  }
  for (const FeedDirection feed : {FeedDirection::u, FeedDirection::v}) {
    for (const std::size_t density : {3u, 17u, 101u, 400u}) {
      ToolPathOptions o;
      o.feed = feed;
      o.lines = density;
      o.points_per_line = density + 2;
      const PathRefused e = refusal(s, o);
      EXPECT_EQ(e.reason(), Refusal::degenerate) << e.what();
      EXPECT_TRUE(contains(e.what(), "S_u x S_v vanishes there")) << e.what();
      EXPECT_TRUE(contains(e.what(), ", 25) mm: ")) << e.what();
      o.unreachable = UnreachablePolicy::clip;
      const ToolPath path = plan_tool_path(s, o);
      // The pole row: the last CC point of each meridian line (feed u), or
      // the whole last line (feed v).
      EXPECT_EQ(path.cuts.degenerate, feed == FeedDirection::u ? o.lines : o.points_per_line);
      EXPECT_EQ(path.cuts.unreachable, 0u);
      for (const ToolPathLine& line : path.lines) {
        for (std::size_t k = 0; k < line.t.size(); ++k) {
          const bool pole = (line.cc[k] - Eigen::Vector3d(0, 0, rho)).norm() < 1e-9;
          EXPECT_EQ(line.state[k] == PointState::degenerate, pole) << k;
          if (pole) continue;
          EXPECT_NEAR((line.normal[k] - line.cc[k] / rho).norm(), 0.0, 1e-9) << k;
          EXPECT_NEAR(line.cl[k].norm(), rho + o.tool_radius, 1e-9);
        }
      }
    }
  }
}

// A concave cylinder (the inside of radius 20, machined from +z): a ball of
// R = 25 cannot fit; R = 15 can, with e = (rho - R)(1 - cos(theta/2)).
TEST(ToolPathGouge, ConcaveFaceWithATooLargeToolIsRefusedOrFlagged) {
  const double rho = 20;
  const NurbsSurface s = testing::cylinder(rho, 210 * kDeg, 330 * kDeg, 30.0);
  ToolPathOptions o;
  o.lines = 3;
  o.points_per_line = 25;
  o.tool_radius = 25;
  const PathRefused e = refusal(s, o, {"face 7 of part.step", nullptr, 1, false});
  EXPECT_EQ(e.reason(), Refusal::gouge);
  EXPECT_TRUE(contains(e.what(), "face 7 of part.step: line 0 (v = 0), CC point 0")) << e.what();
  EXPECT_TRUE(contains(e.what(),
                       "the tool radius R = 25 mm exceeds the surface's smallest concave "
                       "radius of curvature 20 mm there (along the feed 20 mm, across "
                       "it none (convex or flat))"))
      << e.what();
  o.gouge = GougePolicy::allow;
  const ToolPath allowed = plan_tool_path(s, o);
  EXPECT_EQ(allowed.cuts.gouge_allowed, allowed.samples.size());
  EXPECT_EQ(allowed.samples.size(), 3u * 24u);
  o.gouge = GougePolicy::refuse;
  o.tool_radius = 15;
  const ToolPath fits = plan_tool_path(s, o);
  ASSERT_EQ(fits.samples.size(), 3u * 24u);
  for (const PathSample& sample : fits.samples) {
    const ToolPathLine& line = fits.lines[sample.line];
    const std::size_t i = sample.point;
    EXPECT_EQ(line.gouge[i], 0);
    const double theta = std::abs(angle_xz(line.cc[i + 1]) - angle_xz(line.cc[i]));
    EXPECT_NEAR(exact_step_error(line.segment(i)).error, (rho - 15) * (1 - std::cos(theta / 2)),
                kClosedFormTol);
  }
}

// Curvatures against a sphere's and a cylinder's closed forms.
TEST(SurfaceCurvature, MatchesClosedForms) {
  const NurbsSurface sphere = testing::sphere_patch(8.0, 40 * kDeg);
  const SurfaceDerivatives d = surface_derivatives(sphere, 0.3, 0.6);
  const Eigen::Vector3d out = d.point.normalized();
  SurfaceCurvatures k = surface_curvatures(d, out, d.du);
  for (double c : {k.along, k.across, k.max, k.min}) EXPECT_NEAR(c, -1 / 8.0, 1e-12);
  k = surface_curvatures(d, -out, d.dv);  // seen from inside: concave everywhere
  for (double c : {k.along, k.across, k.max, k.min}) EXPECT_NEAR(c, 1 / 8.0, 1e-12);
  const NurbsSurface cylinder = testing::cylinder(4.0, 20 * kDeg, 160 * kDeg, 10.0);
  const SurfaceDerivatives c = surface_derivatives(cylinder, 0.4, 0.5);
  const Eigen::Vector3d radial = Eigen::Vector3d(c.point.x(), 0, c.point.z()).normalized();
  k = surface_curvatures(c, -radial, c.du);  // the inside; u runs round the axis
  EXPECT_NEAR(k.along, 0.25, 1e-12);
  EXPECT_NEAR(k.across, 0.0, 1e-12);
  EXPECT_NEAR(k.max, 0.25, 1e-12);
  EXPECT_NEAR(k.min, 0.0, 1e-12);
  // 45 deg between the feed and the axis: Euler, k = k1 cos^2 + k2 sin^2.
  k = surface_curvatures(c, -radial, c.du.normalized() + c.dv.normalized());
  EXPECT_NEAR(k.along, 0.125, 1e-12);
}

// A plate with a square hole in parameter space.
class PlateWithHole : public FaceDomain {
 public:
  bool contains(const NurbsSurface&, double u, double v) const override {
    return !(u > 0.4 && u < 0.6 && v > 0.3 && v < 0.7);
  }
};

// A flat 100 x 50 mm plate: lines through the hole split into two runs;
// no sample spans the hole; the midpoint check cuts a pair whose two ends
// lie on the face but whose middle does not.
TEST(ToolPathTrims, LinesSplitAroundAHole) {
  NurbsSurface s;
  s.degree_u = s.degree_v = 1;
  s.knots_u = s.knots_v = {0, 0, 1, 1};
  s.count_u = s.count_v = 2;
  s.points = {{0, 0, 0}, {0, 50, 0}, {100, 0, 0}, {100, 50, 0}};
  s.weights.assign(4, 1.0);
  ToolPathOptions o;
  o.lines = 11;
  o.points_per_line = 11;  // u = 0, 0.1, ..., 1: u = 0.5 lies in the hole
  FaceContext face;
  face.domain = std::make_shared<PlateWithHole>();
  const ToolPath path = plan_tool_path(s, o, face);
  for (const ToolPathLine& line : path.lines) {
    const bool through_hole = line.fixed > 0.3 && line.fixed < 0.7;
    if (!through_hole) {
      ASSERT_EQ(line.runs.size(), 1u);
      EXPECT_EQ(line.runs[0].first, 0u);
      EXPECT_EQ(line.runs[0].last, 10u);
      continue;
    }
    ASSERT_EQ(line.runs.size(), 2u) << line.fixed;
    EXPECT_EQ(line.runs[0].first, 0u);
    EXPECT_EQ(line.runs[0].last, 4u);  // u = 0.4 on the face; 0.45 (the middle to 0.5) not
    EXPECT_EQ(line.runs[1].first, 6u);
    EXPECT_EQ(line.runs[1].last, 10u);
    EXPECT_EQ(line.state[5], PointState::outside_face);
  }
  EXPECT_EQ(path.cuts.outside_face, 3u);  // u = 0.5 on the lines v = 0.4, 0.5, 0.6
  EXPECT_EQ(path.samples.size(), 8u * 10u + 3u * 8u);
  for (const PathSample& sample : path.samples) {
    const ToolPathLine& line = path.lines[sample.line];
    EXPECT_TRUE(line.state[sample.point] == PointState::on_path &&
                line.state[sample.point + 1] == PointState::on_path);
    const double mid = 0.5 * (line.t[sample.point] + line.t[sample.point + 1]);
    EXPECT_TRUE(face.domain->contains(s, mid, line.fixed));
  }
}

// A free face is machined from the side that faces the tool over most of
// its area, decided once; a solid's face from outside its material: the
// wall of a hole (its own normal pointing into the hole) is refused from +z.
TEST(ToolPathSide, DecidedOncePerFaceNeverPerPoint) {
  const NurbsSurface s = testing::cylinder(20, 30 * kDeg, 150 * kDeg, 30.0);
  ToolPathOptions o;
  o.lines = 3;
  o.points_per_line = 9;
  FaceContext face;  // S_u x S_v of this arc points into the cylinder
  EXPECT_EQ(plan_tool_path(s, o, face).side, -1);
  face.orientation = -1;  // a reversed face: the same surface, the same side
  EXPECT_EQ(plan_tool_path(s, o, face).side, -1);
  face.orientation = 1;
  face.of_solid = true;  // the wall of a hole: the material lies outside
  const PathRefused e = refusal(s, o, face);
  EXPECT_EQ(e.reason(), Refusal::unreachable);
  EXPECT_TRUE(contains(e.what(), "its material is in the way")) << e.what();
  o.tool_side = ToolSide::back;  // the user's word overrides
  EXPECT_EQ(plan_tool_path(s, o, face).side, -1);
}

TEST(ToolPathOptions, BadValuesNameTheField) {
  ToolPathOptions o;
  o.tool_axis = {0, 0, 0};
  EXPECT_NE(testing::error_message<OptionError>([&] {
              o.validate();
            }).find("tool_axis = [0, 0, 0]: must be a finite direction of non-zero length"),
            std::string::npos);
  o.tool_axis = {0, 1};
  EXPECT_NE(testing::error_message<OptionError>([&] { o.validate(); }).find("must be [x, y, z]"),
            std::string::npos);
  o.tool_axis = {0, 0, 1};
  o.max_normal_angle = 95;
  EXPECT_NE(testing::error_message<OptionError>([&] {
              o.validate();
            }).find("max_normal_angle = 95: must be in (0, 90]"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab
