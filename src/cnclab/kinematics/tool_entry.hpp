#pragma once
// How the cutter reaches the cutting depth of a 2-D pass: never a plunge at a
// fixed XY into solid stock (most end mills do not cut at the centre, and
// those that do are not made for full-diameter drilling).
//
// helix   (default): a helical ramp about a circle the pass already follows,
//          descending at `ramp_angle` from `clearance` above the stock top
//          (z = 0) to the cutting depth and ending at the pass's first point
//          with the pass's direction of rotation. The tool centre's descent
//          per revolution is 2 pi rho tan(ramp_angle) for a helix of radius
//          rho. A helix bore of diameter 2 rho + D leaves no core when
//          2 rho < D (the cutter passes over the helix axis every revolution).
// outside: the groove is open at its start (the stock ends at x = 0): the
//          tool descends beside the stock, `clearance` mm clear of its edge,
//          and feeds along the groove's centreline to the pass's first point.
// Typical ramp angles for end mills are 1-5 degrees (less in steel, more in
// aluminium); 3 degrees is the default (our choice, seed 004 gives no entry).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace cnclab {

struct TrochoidGroove;

enum class EntryMode { helix, outside };
std::string to_string(EntryMode mode);

struct EntryOptions {
  EntryMode mode = EntryMode::helix;
  double ramp_angle = 3.0;  // helix descent angle of the tool centre's path [deg], in (0, 45]
  double clearance = 1.0;   // helix: ramp start above the stock top; outside: from the edge [mm]

  void validate() const;  // OptionError naming the field
};

// The entry's feed moves as tool-centre points (x, y, z); the first point is
// reached by rapid moves from above, the last is (start, cut_z).
struct ToolEntry {
  EntryMode mode = EntryMode::helix;
  std::vector<Eigen::Vector3d> points;
  double revolutions = 0;           // helix: turns of the ramp
  double depth_per_revolution = 0;  // helix: descent per turn [mm]
};

// A helix about `centre` through `start` (radius rho = |start - centre| > 0),
// counter-clockwise when `counter_clockwise`, from z = top_z down to cut_z at
// `ramp_angle_rad`, ending at (start, cut_z); sampled every `max_step_angle`
// radians of turn or finer.
ToolEntry helical_entry(const Eigen::Vector2d& centre, const Eigen::Vector2d& start, double top_z,
                        double cut_z, double ramp_angle_rad, double max_step_angle,
                        bool counter_clockwise = true);

// Down at `outside` from top_z to cut_z, then straight to (start, cut_z).
ToolEntry straight_entry(const Eigen::Vector2d& outside, const Eigen::Vector2d& start, double top_z,
                         double cut_z);

// The entry of a trochoidal groove (kinematics/trochoid.hpp) cut at cut_z < 0:
// helix about the start circle (radius R, the groove's sampling step), or
// from outside the groove's start end at x = -(D/2 + clearance), y = 0.
ToolEntry trochoid_entry(const TrochoidGroove& groove, const EntryOptions& options, double cut_z);

}  // namespace cnclab
