#include "cnclab/motion/feedrate_guess.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace cnclab::feedrate_detail {
namespace {

double max_abs(const std::array<double, 2>& v) {
  return std::max(std::abs(v[0]), std::abs(v[1]));
}

// Heuristic starting point from a state: a speed that ramps up from the
// start state and down to rest with a modest path acceleration and jerk,
// capped at half of what velocity, centripetal acceleration and jerk allow
// at each node; durations, node accelerations and interval jerks follow from
// it by differences.
std::vector<double> heuristic_guess(const std::vector<NodeCoefficients>& nodes, WindowState start) {
  const int N = static_cast<int>(nodes.size()) - 1;
  double acc1_max = 0.0, jerk1_max = 0.0;
  for (const auto& c : nodes) {
    acc1_max = std::max(acc1_max, max_abs(c.acc1));
    jerk1_max = std::max(jerk1_max, max_abs(c.jerk1));
  }
  const double a_guess = 0.2 / acc1_max, j_guess = 0.2 / jerk1_max;
  // Speed after a distance d from rest with path jerk j and acceleration a:
  // jerk phase v = (j/2)(6d/j)^(2/3), then v = sqrt(2 a d).
  auto ramp = [&](double d) {
    return std::min(std::sqrt(2 * a_guess * d), 0.5 * j_guess * std::pow(6 * d / j_guess, 2.0 / 3));
  };
  std::vector<double> v(N + 1), x(4 * N + 2);
  for (int k = 0; k <= N; ++k) {
    const NodeCoefficients& c = nodes[k];
    double cap = c.v_cap;
    if (max_abs(c.vel) > 0) cap = std::min(cap, 1.0 / max_abs(c.vel));
    if (max_abs(c.acc2) > 0) cap = std::min(cap, 1.0 / std::sqrt(max_abs(c.acc2)));
    if (max_abs(c.jerk3) > 0) cap = std::min(cap, std::cbrt(1.0 / max_abs(c.jerk3)));
    const double up = start.v + ramp(c.w - nodes.front().w);
    v[k] = std::min({0.5 * cap, up, ramp(nodes.back().w - c.w)});
  }
  v.front() = start.v;
  v.back() = 0.0;
  std::vector<double> interval_acc(N);
  for (int k = 0; k < N; ++k) {
    const double dw = nodes[k + 1].w - nodes[k].w;
    x[4 * k + 2] = 2 * dw / (v[k] + v[k + 1]);
    interval_acc[k] = (v[k + 1] * v[k + 1] - v[k] * v[k]) / (2 * dw);
  }
  for (int k = 0; k <= N; ++k) {
    x[4 * k] = v[k];
    x[4 * k + 1] = k == 0 ? start.a : k == N ? 0.0 : 0.5 * (interval_acc[k - 1] + interval_acc[k]);
  }
  for (int k = 0; k < N; ++k) x[4 * k + 3] = (x[4 * k + 5] - x[4 * k + 1]) / x[4 * k + 2];
  return x;
}

}  // namespace

// Starting point of a window: the previous window's solution over the
// overlap (feasible, it ends at rest at the previous window's last node),
// then the heuristic from rest over the rest of the window.
std::vector<double> initial_guess(const std::vector<NodeCoefficients>& nodes, WindowState start,
                                  const std::vector<double>& overlap) {
  if (overlap.empty()) return heuristic_guess(nodes, start);
  const std::size_t p = (overlap.size() - 2) / 4;  // nodes 0..p from the previous window
  std::vector<double> x(overlap.begin(), overlap.end() - 2);
  const std::vector<NodeCoefficients> rest(nodes.begin() + p, nodes.end());
  const std::vector<double> tail = heuristic_guess(rest, {0.0, 0.0});
  x.insert(x.end(), tail.begin(), tail.end());
  return x;
}

}  // namespace cnclab::feedrate_detail
