// The cutter's entry to depth, checked on the G-code read back: no feed move
// descends at a fixed XY inside the stock, descents follow the ramp angle,
// and every tool-centre position at depth stays inside the groove (or, for
// the outside entry, outside the stock).
#include "cnclab/kinematics/tool_entry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/kinematics/gcode.hpp"
#include "cnclab/kinematics/trochoid.hpp"

namespace cnclab {
namespace {

struct Move {
  bool rapid = false;
  Eigen::Vector3d from, to;
};

// Modal G00/G01 moves of a program (absolute XYZ words; other words ignored).
std::vector<Move> read_moves(const std::string& program) {
  std::vector<Move> moves;
  Eigen::Vector3d pos(0, 0, 0);
  bool rapid = true;
  std::istringstream lines(program);
  for (std::string line; std::getline(lines, line);) {
    line = line.substr(0, line.find('('));
    std::istringstream words(line);
    Eigen::Vector3d next = pos;
    bool motion = false;
    for (std::string w; words >> w;) {
      if (w == "G00" || w == "G0") rapid = true;
      if (w == "G01" || w == "G1") rapid = false;
      const int axis = w[0] == 'X' ? 0 : w[0] == 'Y' ? 1 : w[0] == 'Z' ? 2 : -1;
      if (axis >= 0) {
        next[axis] = std::stod(w.substr(1));
        motion = true;
      }
    }
    if (motion) moves.push_back({rapid, pos, next});
    pos = next;
  }
  return moves;
}

// Tool-centre region of a closed groove (a slot of width W from x = 0 to L):
// within R = (W - D)/2 of the centreline segment from (W/2, 0) to (L - W/2, 0).
double outside_groove(const TrochoidGrooveOptions& o, const Eigen::Vector2d& p) {
  const double r = (o.groove_width - o.cutter_diameter) / 2;
  const double x = std::clamp(p.x(), o.groove_width / 2, o.groove_length - o.groove_width / 2);
  return (p - Eigen::Vector2d(x, 0)).norm() - r;
}

void check_program(const TrochoidGrooveOptions& g, const EntryOptions& e) {
  const TrochoidGroove groove = make_trochoid_groove(g);
  GcodeOptions o;
  const ToolEntry entry = trochoid_entry(groove, e, o.cut_z);
  const GcodeProgram program = write_gcode(groove.points, o, entry.points);
  const std::vector<Move> moves = read_moves(program.text);
  const double tan_ramp = std::tan(e.ramp_angle * std::numbers::pi / 180);
  const double rounding = 1e-3;  // 3 decimals
  int descents = 0;
  for (const Move& m : moves) {
    const double drop = m.from.z() - m.to.z();
    const double planar = (m.to.head<2>() - m.from.head<2>()).norm();
    // Below the stock top (z < 0) the tool centre is at depth somewhere in
    // the stock: inside the groove, or beside the stock for the outside entry.
    for (const Eigen::Vector3d& p : {m.from, m.to}) {
      if (p.z() >= 0) continue;
      const bool beside_stock =
          e.mode == EntryMode::outside && p.x() < g.groove_width / 2 && std::abs(p.y()) <= rounding;
      if (!beside_stock) {
        EXPECT_LE(outside_groove(g, p.head<2>()), rounding)
            << "(" << p.transpose() << ") leaves the groove";
      }
    }
    if (drop <= 0) continue;
    if (m.rapid) {
      EXPECT_GE(m.to.z(), 0.0) << "a rapid into the stock";
      continue;
    }
    ++descents;
    // A descending feed move inside the stock ramps: XY moves with it, at
    // no more than the ramp angle. Beside the stock (x + D/2 < 0) a vertical
    // feed is allowed.
    const bool beside = m.from.x() + g.cutter_diameter / 2 < 0;
    if (!beside) {
      ASSERT_GT(planar, 0.0) << "a plunge at fixed XY at z " << m.from.z();
      EXPECT_LE(drop, planar * tan_ramp * (1 + 1e-3) + 2 * rounding) << "steeper than the ramp";
    }
  }
  EXPECT_GT(descents, 0);
  EXPECT_EQ(moves.back().to.z(), o.safe_z);  // retracted
}

TEST(ToolEntry, HelicalRampIsTheClosedForm) {
  const Eigen::Vector2d centre(14, 0), start(18, 0);
  const double alpha = 3 * std::numbers::pi / 180;
  const ToolEntry e = helical_entry(centre, start, 1.0, -5.0, alpha, 0.1);
  const double rho = 4.0;
  EXPECT_NEAR(e.depth_per_revolution, 2 * std::numbers::pi * rho * std::tan(alpha), 1e-12);
  EXPECT_NEAR(e.revolutions, 6.0 / e.depth_per_revolution, 1e-12);
  EXPECT_EQ(e.points.front().z(), 1.0);
  EXPECT_EQ(e.points.back(), Eigen::Vector3d(18, 0, -5));
  for (std::size_t i = 0; i < e.points.size(); ++i) {
    const Eigen::Vector3d& p = e.points[i];
    EXPECT_NEAR((p.head<2>() - centre).norm(), rho, 1e-12);
    if (i == 0) continue;
    // z falls by rho tan(alpha) per radian turned, counter-clockwise.
    const Eigen::Vector2d a = e.points[i - 1].head<2>() - centre, b = p.head<2>() - centre;
    const double turn = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    EXPECT_GT(turn, 0.0);
    EXPECT_LE(turn, 0.1 + 1e-12);
    EXPECT_NEAR(e.points[i - 1].z() - p.z(), turn * rho * std::tan(alpha), 1e-9);
  }
}

TEST(ToolEntry, Table2GrooveByHelixHasNoPlungeAndStaysInTheGroove) {
  check_program(TrochoidGrooveOptions{}, EntryOptions{});
  EntryOptions steep;
  steep.ramp_angle = 10;
  TrochoidGrooveOptions narrow;
  narrow.groove_width = 22;
  narrow.groove_length = 60;
  narrow.step = 1.0;
  check_program(narrow, steep);
}

TEST(ToolEntry, FromOutsideTheStockFeedsInAlongTheCentreline) {
  EntryOptions e;
  e.mode = EntryMode::outside;
  check_program(TrochoidGrooveOptions{}, e);
  const TrochoidGroove groove = make_trochoid_groove(TrochoidGrooveOptions{});
  const ToolEntry entry = trochoid_entry(groove, e, -5);
  EXPECT_EQ(entry.points.front(), Eigen::Vector3d(-11, 0, 1));  // D/2 + 1 mm beside the edge
}

TEST(ToolEntry, PlungeWithoutEntryIsWhatTheCheckCatches) {
  // The check has teeth: the plain plunge form fails it.
  const TrochoidGroove groove = make_trochoid_groove(TrochoidGrooveOptions{});
  const std::vector<Move> moves = read_moves(write_gcode(groove.points, GcodeOptions{}).text);
  const auto plunge = std::find_if(moves.begin(), moves.end(), [](const Move& m) {
    return !m.rapid && m.to.z() < m.from.z() && m.to.head<2>() == m.from.head<2>();
  });
  EXPECT_NE(plunge, moves.end());
}

TEST(ToolEntry, BadOptionsAreClearErrors) {
  EntryOptions e;
  e.ramp_angle = 0;
  EXPECT_THROW(e.validate(), OptionError);
  e = {};
  e.clearance = -1;
  EXPECT_THROW(e.validate(), OptionError);
  const TrochoidGroove groove = make_trochoid_groove(TrochoidGrooveOptions{});
  const ToolEntry entry = trochoid_entry(groove, EntryOptions{}, -5);
  GcodeOptions o;
  o.cut_z = -4;  // the entry ends at -5
  EXPECT_THROW(write_gcode(groove.points, o, entry.points), Error);
}

}  // namespace
}  // namespace cnclab
