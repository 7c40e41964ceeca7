#include "cnclab/kinematics/tool_entry.hpp"

#include <cmath>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/kinematics/trochoid.hpp"

namespace cnclab {

std::string to_string(EntryMode mode) {
  return mode == EntryMode::helix ? "helix" : "outside";
}

void EntryOptions::validate() const {
  if (!(ramp_angle > 0 && ramp_angle <= 45)) {
    throw OptionError("ramp_angle", shortest_double(ramp_angle),
                      "must be in (0, 45] degrees (typical: 1-5 for end mills)");
  }
  if (!(clearance > 0) || !std::isfinite(clearance)) {
    throw OptionError("clearance", shortest_double(clearance), "must be a finite length > 0 mm");
  }
}

ToolEntry helical_entry(const Eigen::Vector2d& centre, const Eigen::Vector2d& start, double top_z,
                        double cut_z, double ramp_angle_rad, double max_step_angle,
                        bool counter_clockwise) {
  const double rho = (start - centre).norm();
  if (!(rho > 0) || !(top_z > cut_z) || !(ramp_angle_rad > 0) || !(max_step_angle > 0)) {
    throw Error("helical entry: needs a radius > 0, top_z > cut_z and positive angles");
  }
  ToolEntry e;
  e.mode = EntryMode::helix;
  e.depth_per_revolution = 2 * std::numbers::pi * rho * std::tan(ramp_angle_rad);
  // Turn angle to descend top_z - cut_z: z falls by rho tan(alpha) per radian.
  const double turn = (top_z - cut_z) / (rho * std::tan(ramp_angle_rad));
  e.revolutions = turn / (2 * std::numbers::pi);
  const auto steps = static_cast<int>(std::ceil(turn / max_step_angle));
  const double sense = counter_clockwise ? 1.0 : -1.0;
  const double end_angle = std::atan2(start.y() - centre.y(), start.x() - centre.x());
  for (int k = 0; k <= steps; ++k) {
    const double remaining = turn * (steps - k) / steps;  // turn still to go
    const double a = end_angle - sense * remaining;
    const Eigen::Vector2d xy =
        k == steps ? start
                   : Eigen::Vector2d(centre + rho * Eigen::Vector2d(std::cos(a), std::sin(a)));
    // The ends exactly (no rounding of the turn): top_z first, cut_z last.
    const double z = k == 0       ? top_z
                     : k == steps ? cut_z
                                  : cut_z + remaining * rho * std::tan(ramp_angle_rad);
    e.points.emplace_back(xy.x(), xy.y(), z);
  }
  return e;
}

ToolEntry straight_entry(const Eigen::Vector2d& outside, const Eigen::Vector2d& start, double top_z,
                         double cut_z) {
  ToolEntry e;
  e.mode = EntryMode::outside;
  e.points = {{outside.x(), outside.y(), top_z},
              {outside.x(), outside.y(), cut_z},
              {start.x(), start.y(), cut_z}};
  return e;
}

ToolEntry trochoid_entry(const TrochoidGroove& groove, const EntryOptions& options, double cut_z) {
  options.validate();
  if (!(cut_z < 0))
    throw OptionError("cut_z", shortest_double(cut_z), "must be below the stock top z = 0");
  const Eigen::Vector2d start = groove.points.front();
  if (options.mode == EntryMode::outside) {
    const double x = -(groove.options.cutter_diameter / 2 + options.clearance);
    return straight_entry({x, 0.0}, start, options.clearance, cut_z);
  }
  // The loops run counter-clockwise (trochoid.hpp); the start circle's centre.
  return helical_entry({groove.centre_start, 0.0}, start, options.clearance, cut_z,
                       options.ramp_angle * std::numbers::pi / 180, groove.dt);
}

}  // namespace cnclab
