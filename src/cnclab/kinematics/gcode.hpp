#pragma once
// ISO 6983 (G-code) for a 2-D contour at constant depth: header with units,
// plane, absolute mode and feed mode; spindle on; rapid to the start above
// the part; the entry to the cutting depth (a plunge, or the feed moves of a
// ramp, kinematics/tool_entry.hpp); N-numbered G01 moves; safe retract;
// spindle off; M30. Without an entry (below, the plunge form):
//
//   %
//   O1000 (title)
//   N10 G21 G17 G90 G94
//   N20 G00 Z5.000
//   N30 S3000 M03
//   N40 G00 X... Y...
//   N50 G01 Z-5.000 F200.
//   N60 G01 X... Y... F800.
//   N70 G01 X... Y...
//   ...
//   N.. G00 Z5.000
//   N.. M05
//   N.. M30
//   %
#include <Eigen/Core>
#include <ostream>
#include <span>
#include <string>

namespace cnclab {

struct GcodeOptions {
  int program_number = 1000;      // O-word, 1..9999
  std::string title;              // comment after the O-word (no parentheses)
  double feed = 800.0;            // G01 feed in the plane [mm/min]
  double plunge_feed = 200.0;     // G01 feed of the plunge or entry moves [mm/min]
  double spindle_speed = 3000.0;  // S-word [rpm]
  double safe_z = 5.0;            // retract height above the part top (z = 0) [mm]
  double cut_z = -5.0;            // cutting depth [mm], below safe_z
  int line_increment = 10;        // N-word step, >= 1
  int decimals = 3;               // coordinate decimals, 0..6

  // Finite, feeds and speed > 0, cut_z < safe_z, ranges as stated, title
  // free of '(' and ')'.
  void validate() const;
};

// "X-4.000 Y-14.750" style coordinate words; never "-0.000".
std::string coordinate_words(const Eigen::Vector2d& p, int decimals);

struct GcodeProgram {
  std::string text;
  std::vector<int> point_line_numbers;  // N-word of each path point's block
};

// The program for `path` (>= 2 points, all finite; else cnclab::Error).
// `entry` (optional, tool_entry.hpp): feed moves (x, y, z) ending at
// (path[0], cut_z); the tool rapids to above entry[0], down to entry[0]'s z
// (which must be between cut_z and safe_z), then feeds along the entry at
// plunge_feed. Without it, the tool plunges at path[0].
GcodeProgram write_gcode(std::span<const Eigen::Vector2d> path, const GcodeOptions& options,
                         std::span<const Eigen::Vector3d> entry = {});

}  // namespace cnclab
