#pragma once
// Starting points of the feedrate NLP windows (feedrate_nlp.hpp layout).
#include <vector>

#include "cnclab/motion/feedrate_nlp.hpp"

namespace cnclab::feedrate_detail {

// Starting point of a window that starts in state `start`: the previous
// window's solution over the overlap (`overlap`: its variables from this
// window's first node on; feasible, it ends at rest at the previous window's
// last node), then a heuristic from rest over the rest of the window (a
// speed ramping up and down with modest path acceleration and jerk, capped
// at half of what velocity, centripetal acceleration and jerk allow at each
// node). With `overlap` empty the heuristic starts from `start`.
std::vector<double> initial_guess(const std::vector<NodeCoefficients>& nodes, WindowState start,
                                  const std::vector<double>& overlap);

}  // namespace cnclab::feedrate_detail
