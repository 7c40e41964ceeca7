// Trochoidal groove path (Eq. 6), radial engagement (closed forms), the
// trochoid fit, and the G-code writer.
#include "cnclab/kinematics/trochoid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/kinematics/engagement.hpp"
#include "cnclab/kinematics/gcode.hpp"
#include "cnclab/kinematics/trochoid_fit.hpp"

namespace cnclab {
namespace {

TEST(TrochoidGroove, Table2GeometryDerived) {
  const TrochoidGroove g = make_trochoid_groove({});  // Table 2: D 20, W 28, L 120, step 1.5
  EXPECT_DOUBLE_EQ(g.radius, 4.0);                    // (28 - 20) / 2
  EXPECT_DOUBLE_EQ(g.centre_travel, 92.0);            // 120 - 28
  EXPECT_EQ(g.loops, 62u);                            // ceil(92 / 1.5) = ceil(61.33)
  EXPECT_NEAR(g.advance, 92.0 / 62.0, 1e-15);         // 1.4839 mm <= 1.5
  EXPECT_NEAR(g.speed, g.advance / (2 * std::numbers::pi), 1e-15);
  ASSERT_EQ(g.points.size(), (g.loops + 2) * g.samples_per_loop + 1);
  // Starts and ends at angle 0 of the start / end circles.
  EXPECT_NEAR(g.points.front().x(), 14.0 + 4.0, 1e-12);
  EXPECT_NEAR(g.points.back().x(), 120.0 - 14.0 + 4.0, 1e-9);
  EXPECT_NEAR(g.points.back().y(), 0.0, 1e-9);
}

// The tool (radius D/2 around the path) stays inside the groove and reaches
// its walls and both ends: max |y| + D/2 = W/2, min x - D/2 = 0, max x + D/2 = L,
// up to the sampling (a vertex misses an extreme by at most the chord tolerance).
TEST(TrochoidGroove, ToolStaysInsideAndReachesTheGrooveBoundary) {
  const TrochoidGroove g = make_trochoid_groove({});
  const double tol = g.options.chord_tolerance;
  double ymax = 0, xmin = 1e9, xmax = -1e9;
  for (const auto& p : g.points) {
    ymax = std::max(ymax, std::abs(p.y()));
    xmin = std::min(xmin, p.x());
    xmax = std::max(xmax, p.x());
  }
  EXPECT_NEAR(ymax + 10, 14.0, tol);
  EXPECT_LE(ymax + 10, 14.0 + 1e-12);
  EXPECT_NEAR(xmin - 10, 0.0, tol);
  EXPECT_GE(xmin - 10, -1e-12);
  EXPECT_NEAR(xmax + 10, 120.0, 1e-9);
}

// Every chord's midpoint lies within chord_tolerance of the true curve
// (evaluated at the mid parameter, an upper bound of the distance).
TEST(TrochoidGroove, ChordDeviationWithinTolerance) {
  TrochoidGrooveOptions o;
  o.chord_tolerance = 0.01;
  const TrochoidGroove g = make_trochoid_groove(o);
  const double t_loops = 2 * std::numbers::pi * static_cast<double>(g.loops);
  for (std::size_t k = 1; k < g.points.size(); ++k) {
    const double tm = 0.5 * (g.t[k - 1] + g.t[k]);
    const double centre =
        g.centre_start + g.speed * std::clamp(tm - 2 * std::numbers::pi, 0.0, t_loops);
    const Eigen::Vector2d curve(centre + g.radius * std::cos(tm), g.radius * std::sin(tm));
    const Eigen::Vector2d mid = 0.5 * (g.points[k - 1] + g.points[k]);
    ASSERT_LE((curve - mid).norm(), o.chord_tolerance * 1.0001) << k;
  }
  // Within the loops the path is Eq. 6 shifted to the start centre.
  for (std::size_t k = g.samples_per_loop; k < 3 * g.samples_per_loop; ++k) {
    const Eigen::Vector2d eq6 = trochoid_point(g.radius, g.speed, g.t[k] - 2 * std::numbers::pi);
    ASSERT_NEAR(g.points[k].x(), g.centre_start + eq6.x(), 1e-9);
    ASSERT_NEAR(g.points[k].y(), eq6.y(), 1e-12);
  }
}

std::string option_field(const TrochoidGrooveOptions& o) {
  try {
    o.validate();
  } catch (const OptionError& e) {
    return e.field() + ": " + e.rule();
  }
  return "";
}

TEST(TrochoidGroove, DegenerateGroovesAreClearErrors) {
  TrochoidGrooveOptions o;
  o.cutter_diameter = 30;  // wider than the 28 mm groove
  EXPECT_NE(option_field(o).find("cutter_diameter: must be smaller than groove_width 28"),
            std::string::npos);
  o.cutter_diameter = 28;  // as wide: slotting, R = 0
  EXPECT_NE(option_field(o).find("cutter_diameter"), std::string::npos);
  o = {};
  o.step = 0;
  EXPECT_NE(option_field(o).find("step: must be a finite advance per loop > 0"), std::string::npos);
  o.step = -1;
  EXPECT_NE(option_field(o).find("step"), std::string::npos);
  o.step = 9;  // > 2R = 8
  EXPECT_NE(option_field(o).find("wider steps leave material"), std::string::npos);
  o = {};
  o.groove_length = 20;
  EXPECT_NE(option_field(o).find("groove_length"), std::string::npos);
  o = {};
  o.chord_tolerance = std::nan("");
  EXPECT_NE(option_field(o).find("chord_tolerance"), std::string::npos);
  EXPECT_THROW(make_trochoid_groove(o), OptionError);
}

std::vector<Eigen::Vector2d> line(Eigen::Vector2d from, Eigen::Vector2d to, double spacing) {
  return densify(std::vector<Eigen::Vector2d>{from, to}, spacing);
}

// Straight slotting in full stock: pi + 2 asin(s / 2r) at every position
// after the plunge (the arc behind lies in the previous disc).
TEST(Engagement, StraightSlottingIsHalfTheCircle) {
  constexpr double r = 10, s = 0.05;
  const auto path = line({0, 0}, {40, 0}, s);
  const auto e = engagement_angles(path, r);
  ASSERT_EQ(e.size(), path.size());
  EXPECT_NEAR(e[0].angle, 2 * std::numbers::pi, 1e-12);  // plunge
  for (std::size_t k = 1; k < e.size(); ++k) {
    ASSERT_NEAR(e[k].angle, std::numbers::pi + 2 * std::asin(s / (2 * r)), 1e-9) << k;
  }
}

// A second pass beside a first one at radial depth a_e = 3 mm: up-milling
// engagement acos(1 - a_e / r) plus the step term asin(s / 2r), once the
// tool is clear of the start (x > 2r).
TEST(Engagement, SideMillingAtRadialDepthMatchesTheClosedForm) {
  constexpr double r = 10, s = 0.01, ae = 3;
  auto path = line({-30, 0}, {60, 0}, s);  // first pass: strip |y| < r removed
  const std::size_t first = path.size();
  const auto second = line({-30, ae}, {60, ae}, s);
  path.insert(path.end(), second.begin(), second.end());
  const auto e = engagement_angles(path, r, 97);
  const double expected = std::acos(1 - ae / r) + std::asin(s / (2 * r));
  int checked = 0;
  for (const auto& sample : e) {
    if (sample.index <= first) continue;
    const double x = path[sample.index].x();
    if (x < -30 + 2 * r || x > 50) continue;
    // Between first-pass discs the strip edge is scalloped by s^2 / (8r):
    // negligible here (angle change ~ 1e-6 rad).
    ASSERT_NEAR(sample.angle, expected, 1e-4) << x;
    ++checked;
  }
  EXPECT_GT(checked, 50);
}

TEST(Engagement, RepeatedPositionCutsNothing) {
  const std::vector<Eigen::Vector2d> path = {{0, 0}, {1, 0}, {1, 0}};
  const auto e = engagement_angles(path, 5);
  EXPECT_EQ(e[2].angle, 0.0);
  EXPECT_THROW(engagement_angles(path, 0), Error);
  EXPECT_THROW(densify(path, -1), Error);
}

// The trochoid engages the stock far less than slotting (180 deg) once past
// the entry circle.
TEST(Engagement, TrochoidSteadyStateIsBelowSlotting) {
  TrochoidGrooveOptions o;
  o.groove_length = 40;  // short groove: fast
  const TrochoidGroove g = make_trochoid_groove(o);
  const auto dense = densify(g.points, 0.1);
  const auto e = engagement_angles(dense, 10, 5);
  double steady = 0;
  for (const auto& s : e) {
    if (dense[s.index].x() > 14 + 4 + 2 && dense[s.index].x() < 40 - 14 - 4) {
      steady = std::max(steady, s.angle);
    }
  }
  EXPECT_GT(steady, 0.2);
  EXPECT_LT(steady, std::numbers::pi / 2);
}

// The fit recovers known parameters from points rounded to 4 decimals (as in
// Table 3) with residuals at the rounding level.
TEST(TrochoidFit, RecoversKnownParametersFromRoundedPoints) {
  const TrochoidParameters truth{0.3, -14.2, 0.25, -0.1, 3.8, 1.07, 3.0};
  std::vector<double> t;
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i < 12; ++i) {
    t.push_back(0.2 * i);
    const Eigen::Vector2d p = trochoid_model(truth, t.back());
    pts.emplace_back(std::round(p.x() * 1e4) / 1e4, std::round(p.y() * 1e4) / 1e4);
  }
  const TrochoidFit fit = fit_trochoid(t, pts);
  EXPECT_LT(fit.rms, 5e-5);
  EXPECT_NEAR(fit.parameters.radius, truth.radius, 2e-2);
  EXPECT_NEAR(fit.parameters.omega, truth.omega, 2e-3);
  EXPECT_NEAR(fit.parameters.vx, truth.vx, 2e-2);
  EXPECT_NEAR(fit.parameters.vy, truth.vy, 2e-2);
  EXPECT_NEAR(advance_per_turn(truth), 2 * std::numbers::pi * std::hypot(0.25, 0.1) / 1.07, 1e-12);
  EXPECT_THROW(fit_trochoid(std::vector<double>{1, 2}, std::vector<Eigen::Vector2d>(2)), Error);
}

// Seed 004 Table 3 (transcribed in results/reference/trochoid_table3.csv) is
// Eq. 6 advancing along +y: x = -4 cos t, y = -14.75 + t / (2 pi) - 4 sin t
// (R = 4, w = 1, 1 mm per turn, phase 180 deg), to its 4-decimal rounding;
// the fit finds those values.
TEST(TrochoidFit, Seed004Table3IsEq6AdvancingAlongY) {
  std::ifstream in(std::string(CNCLAB_SOURCE_DIR) + "/results/reference/trochoid_table3.csv");
  ASSERT_TRUE(in);
  std::vector<double> t;
  std::vector<Eigen::Vector2d> pts;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    std::stringstream ss(line);
    std::string a, b, c;
    std::getline(ss, a, ',');
    std::getline(ss, b, ',');
    std::getline(ss, c, ',');
    t.push_back(std::stod(a));
    pts.emplace_back(std::stod(b), std::stod(c));
  }
  ASSERT_EQ(t.size(), 12u);
  for (std::size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(pts[i].x(), -4 * std::cos(t[i]), 5.01e-5) << t[i];
    EXPECT_NEAR(pts[i].y(), -14.75 + t[i] / (2 * std::numbers::pi) - 4 * std::sin(t[i]), 5.01e-5)
        << t[i];
  }
  const TrochoidFit fit = fit_trochoid(t, pts);
  EXPECT_LT(fit.rms, 1e-4);
  EXPECT_NEAR(fit.parameters.radius, 4.0, 1e-2);
  EXPECT_NEAR(std::abs(fit.parameters.omega), 1.0, 1e-3);
  EXPECT_NEAR(advance_per_turn(fit.parameters), 1.0, 1e-2);
  EXPECT_NEAR(fit.parameters.vx, 0.0, 1e-3);
}

TEST(Gcode, ProgramStructureAndWords) {
  const std::vector<Eigen::Vector2d> path = {{-4, -14.75}, {-3.92034, -15.51276}, {1e-5, -2e-4}};
  GcodeOptions o;
  o.title = "test";
  const GcodeProgram p = write_gcode(path, o);
  const std::string expected =
      "%\n"
      "O1000 (test)\n"
      "N10 G21 G17 G90 G94 (mm, XY plane, absolute, feed per minute)\n"
      "N20 G00 Z5.000\n"
      "N30 S3000 M03\n"
      "N40 G00 X-4.000 Y-14.750\n"
      "N50 G01 Z-5.000 F200.\n"
      "N60 G01 X-3.920 Y-15.513 F800.\n"
      "N70 G01 X0.000 Y0.000\n"
      "N80 G00 Z5.000 (safe retract)\n"
      "N90 M05\n"
      "N100 M30\n"
      "%\n";
  EXPECT_EQ(p.text, expected);
  EXPECT_EQ(p.point_line_numbers, (std::vector<int>{40, 60, 70}));
  o.cut_z = 10;
  EXPECT_THROW(write_gcode(path, o), OptionError);
  o = {};
  o.title = "bad (comment)";
  EXPECT_THROW(write_gcode(path, o), OptionError);
  EXPECT_THROW(write_gcode(std::vector<Eigen::Vector2d>{{0, 0}}, GcodeOptions{}), Error);
}

}  // namespace
}  // namespace cnclab
