#pragma once
// Internal to the feedrate planner: the limit refinement after the windows
// (feedrate_planner.hpp explains why; LimitRefinementOptions configure it).
#include "cnclab/motion/feedrate_solver.hpp"

namespace cnclab::feedrate_detail {

// Checks `plan` between its nodes and, up to options.refinement.max_rounds
// times, bisects every interval exceeding a limit by more than the tolerance
// and replans a local window around each group of them (refinement.margin
// intervals on each side, ends fixed to the current plan's states; if Ipopt
// fails there, once more with window_intervals - commit_intervals, room for a
// full stop). Updates plan in place.
LimitRefinementSummary refine_limits(const PlanarPath& path, const FeedratePlannerOptions& options,
                                     const Scaling& scaling, WindowSolver& solver,
                                     ScaledPlan& plan);

}  // namespace cnclab::feedrate_detail
