#pragma once
// Umbrella header of the motion module: planar paths, jerk-limited feedrate
// planning with Ipopt, the 1 ms interpolator, the simulated feed drives,
// the csaps-equivalent smoothing spline and contour errors (docs/motion.md).
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/axis_limits.hpp"
#include "cnclab/motion/constant_feed_reference.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "cnclab/motion/feed_drive.hpp"
#include "cnclab/motion/feedrate_bounds.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/feedrate_profile.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/limit_check.hpp"
#include "cnclab/motion/machine.hpp"
#include "cnclab/motion/path_grid.hpp"
#include "cnclab/motion/path_speed_cap.hpp"
#include "cnclab/motion/planar_path.hpp"
#include "cnclab/motion/reference_trajectory.hpp"
#include "cnclab/motion/scurve.hpp"
#include "cnclab/motion/smoothing_spline.hpp"
