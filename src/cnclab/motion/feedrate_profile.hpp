#pragma once
// A planned feedrate: the path parameter u(t) as a piecewise cubic in time
// (constant d3u/dt3 on each interval between grid nodes), continuous in u,
// du/dt and d2u/dt2 to the solver tolerance.
#include <array>
#include <cstddef>
#include <vector>

namespace cnclab {

// u and its time derivatives at one instant.
struct ParameterState {
  double u = 0.0;     // path parameter
  double ud = 0.0;    // du/dt [1/s]
  double udd = 0.0;   // d2u/dt2 [1/s^2]
  double uddd = 0.0;  // d3u/dt3 [1/s^3]
};

// Per-window solver record.
struct WindowRecord {
  std::size_t first_node = 0, last_node = 0;  // grid nodes covered by the NLP
  std::size_t committed_nodes = 0;            // nodes kept from this window
  int iterations = 0;                         // Ipopt iterations
  double seconds = 0.0;                       // wall time of the solve
};

// Peak |axis derivative| / axis limit, per axis [0] = x, [1] = y.
struct LimitRatios {
  std::array<double, 2> velocity{}, acceleration{}, jerk{};

  double worst() const;                    // largest of the six
  void include(const LimitRatios& other);  // elementwise max
};

// The limit refinement after planning (feedrate_planner.hpp,
// LimitRefinementOptions): between grid nodes the exact cubic motion can
// exceed the limits imposed at the nodes; the planner checks the plan between
// nodes, bisects the grid intervals that exceed a limit and replans local
// windows around them until every ratio is within 1 + tolerance.
struct LimitRefinementSummary {
  int rounds = 0;                // rounds of bisection and local replanning run
  std::size_t local_solves = 0;  // local NLP windows solved, all rounds
  std::size_t widened = 0;       // of them: solved again with the wide margin
  int local_iterations = 0;      // their Ipopt iterations, summed
  std::size_t bisected = 0;      // grid intervals split in two, all rounds
  double initial_time = 0.0;     // traversal time before refinement [s]
  LimitRatios initial, final;    // peak ratios before / after refinement
  bool converged = false;        // final.worst() <= 1 + tolerance
  double seconds = 0.0;          // wall time of checks and local solves
};

struct FeedrateProfile {
  // Grid nodes 0..N: parameter, time [s], du/dt, d2u/dt2.
  std::vector<double> u, t, ud, udd;
  // Intervals 0..N-1: constant d3u/dt3 [1/s^3]; duration = t[k+1] - t[k].
  std::vector<double> uddd;
  std::vector<WindowRecord> windows;
  LimitRefinementSummary refinement;

  double total_time() const { return t.empty() ? 0.0 : t.back(); }
  std::size_t intervals() const { return uddd.size(); }
  // State at time `time` (clamped to [0, total_time()]), from the cubic of
  // the interval holding it, evaluated from the interval's start node.
  ParameterState at(double time) const;
  // State `tau` seconds after node k, on interval k's cubic (k < intervals()).
  ParameterState in_interval(std::size_t k, double tau) const;
};

// The same path motion slowed down uniformly (a feed override): u~(t) =
// u(f t) with 0 < f <= 1, so t~ = t / f, du/dt f, d2u/dt2 f^2, d3u/dt3 f^3.
// Every axis velocity scales by f, acceleration by f^2, jerk by f^3, so the
// axis limits still hold. Windows and refinement records are dropped.
// OptionError("factor") unless 0 < factor <= 1.
FeedrateProfile time_scaled(const FeedrateProfile& profile, double factor);

}  // namespace cnclab
