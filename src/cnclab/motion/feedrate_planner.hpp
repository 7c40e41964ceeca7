#pragma once
// Minimum-time feedrate along a planar path under per-axis velocity,
// acceleration and jerk limits, as a nonlinear program over the path
// parameter solved with Ipopt (C++ TNLP interface, exact sparse Jacobian and
// exact Hessian of the Lagrangian; formulation in feedrate_nlp.hpp).
//
// Why exact second derivatives, not limited-memory quasi-Newton: every
// constraint is a polynomial of degree <= 4 in at most four variables, so
// the Hessian is a few entries per node, cheap and exact (checked against
// finite differences). Measured on 2 turns of the epitrochoid test path
// (8 windows): both need 32 iterations per window to the same optimum, but
// Ipopt's L-BFGS costs 16.8 ms per iteration against 7-8 ms with the exact
// Hessian, whose sparse KKT system MUMPS factorises directly.
//
// Long paths are solved in overlapping windows: a window of
// `window_intervals` grid intervals starts from the state (du/dt, d2u/dt2)
// matched to the previous window at that node and ends at rest (so every
// committed prefix can still stop: the plan is feasible whatever follows);
// its first `commit_intervals` intervals are kept and the next window starts
// at the last kept node. The overlap must exceed the braking distance
// (40 mm at seed 002's limits, see validate()) for the rest
// condition at a window's end not to slow the kept part.
//
// Limit refinement: the limits hold at the grid nodes, but between nodes the
// exact cubic motion follows the path geometry and can exceed them (on seed
// 002's random NURBS path at a 1 mm grid: the axis jerk by up to 4.2 %). After
// the windows, every interval is checked (limit_check.hpp); intervals
// exceeding a limit by more than the tolerance are bisected, and a local
// window around them (refinement.margin intervals on each side) is replanned
// between the current plan's states at its ends. Rounds repeat until every interval holds
// (the summary in FeedrateProfile::refinement says how it went).
#include <cstddef>

#include "cnclab/core/progress.hpp"
#include "cnclab/motion/axis_limits.hpp"
#include "cnclab/motion/feedrate_profile.hpp"
#include "cnclab/motion/path_speed_cap.hpp"
#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

// The check and refinement after planning (see above and docs/motion.md).
struct LimitRefinementOptions {
  // Allowed excess: every checked |q'_i| / V_i, |q''_i| / A_i, |q'''_i| / J_i
  // <= 1 + tolerance. In (0, 0.5].
  double tolerance = 0.005;
  // Rounds of bisection and local replanning, >= 0; 0 = check only (the plan
  // is unchanged, the summary still reports the peak ratios). Each round
  // cuts an interval's excess to about a quarter (it scales with the
  // interval's duration squared); the seed 002 study's path needs 4.
  int max_rounds = 10;
  // Instants checked per interval: samples + 1, equally spaced in time, both
  // ends included. >= 1.
  int samples = 8;
  // Grid intervals on each side of an exceeding one replanned with it, >= 1.
  // The default, the planner's window overlap, holds a full stop, so the
  // local problem is feasible. A smaller margin is tried first and, if Ipopt
  // fails on it, widened to window_intervals - commit_intervals and solved
  // again; measured on the study path, 40 needed 5 such retries (failed
  // solves are slow) and cost more CPU time than 60.
  std::size_t margin = 60;

  void validate() const;  // OptionError naming the field
};

struct FeedratePlannerOptions {
  PlanarLimits limits;  // per-axis v, a, j (seed 002: 300, 2000, 50000)
  // Arc length between grid nodes [mm]. Limits are imposed at the nodes;
  // between nodes the exact cubic motion follows the path geometry and may
  // exceed them by a few % at 1 mm; `refinement` bisects the grid where it
  // does, which costs far less than a uniformly finer grid.
  double grid_spacing = 1.0;
  // Near the rest states at both path ends the jerk-limited motion starts as
  // s = J t^3 / 6: the first A^3 / (6 J^2) = 0.53 mm (seed 002's limits) are
  // a pure jerk phase. Grid intervals within end_refinement_length [mm] of an
  // end are split into end_refinement equal parts so that phase is resolved
  // (on a line the planned time then stays within 0.5 % of the S-curve with
  // grid_spacing = 1 mm; without it the first interval alone costs ~1 %).
  double end_refinement_length = 4.0;
  std::size_t end_refinement = 8;      // >= 1; 1 = off
  std::size_t window_intervals = 720;  // intervals per NLP window
  // Intervals kept per window (< window_intervals); the other 60 mm are the
  // overlap. Cost per path length ~ window / commit at a roughly constant
  // iteration count: 240/180 costs 0.7x of 120/60, and 720/660 0.85x of
  // 240/180 (planning CPU time, 20 turns of the benchmark epitrochoid:
  // 33.4 s against 39.5 s, 36 against 34 Ipopt iterations per window, the
  // same 53.09 s traversal time; scripts/bench_motion 20 WINDOW COMMIT).
  std::size_t commit_intervals = 660;
  double tolerance = 1e-8;            // Ipopt `tol` (scaled NLP, see feedrate_nlp.hpp)
  int max_iterations = 500;           // Ipopt `max_iter` per window
  RegularityOptions regularity;       // cusp check before planning
  LimitRefinementOptions refinement;  // limits checked and enforced between nodes
  // Optional path-speed bound |C'| du/dt <= speed_cap(u) at every grid node
  // (an upper bound on the NLP's v_k beside the axis velocity limits);
  // empty = none. The contour-error feedrate optimisation lowers it where
  // the predicted contour error exceeds the tolerance.
  PathSpeedCap speed_cap;

  void validate() const;
};

// Throws OptionError for bad options, cnclab::Error for a path with a cusp,
// and cnclab::Error naming the window (or the refinement round and local
// window), its nodes, its parameter range and Ipopt's status when a solve
// fails. A refinement that has not converged after max_rounds is a result,
// not an error: profile.refinement.converged is false. `progress` (optional)
// hears of every window solved.
FeedrateProfile plan_feedrate(const PlanarPath& path, const FeedratePlannerOptions& options = {},
                              const ProgressCallback& progress = {});

}  // namespace cnclab
