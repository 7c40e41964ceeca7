#pragma once
// A planned feedrate: the path parameter u(t) as a piecewise cubic in time
// (constant d3u/dt3 on each interval between grid nodes), continuous in u,
// du/dt and d2u/dt2 to the solver tolerance.
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

struct FeedrateProfile {
  // Grid nodes 0..N: parameter, time [s], du/dt, d2u/dt2.
  std::vector<double> u, t, ud, udd;
  // Intervals 0..N-1: constant d3u/dt3 [1/s^3]; duration = t[k+1] - t[k].
  std::vector<double> uddd;
  std::vector<WindowRecord> windows;

  double total_time() const { return t.empty() ? 0.0 : t.back(); }
  // State at time `time` (clamped to [0, total_time()]), from the cubic of
  // the interval holding it, evaluated from the interval's start node.
  ParameterState at(double time) const;
};

}  // namespace cnclab
