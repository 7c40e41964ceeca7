#include "cnclab/motion/feedrate_planner.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/motion/feedrate_guess.hpp"
#include "cnclab/motion/feedrate_refinement.hpp"
#include "cnclab/motion/feedrate_solver.hpp"
#include "cnclab/motion/path_grid.hpp"

namespace cnclab {
namespace {

using feedrate_detail::initial_guess;
using feedrate_detail::ScaledPlan;
using feedrate_detail::Scaling;
using feedrate_detail::WindowSolution;
using feedrate_detail::WindowSolver;
using feedrate_detail::WindowState;

// Splits the grid intervals that start or end within `length` mm of arc from
// a path end into `parts` equal parameter steps.
std::vector<double> refine_ends(const PlanarPath& path, const std::vector<double>& grid,
                                double length, std::size_t parts) {
  if (parts <= 1 || length <= 0.0) return grid;
  std::vector<double> s(grid.size(), 0.0);  // arc length at each node
  for (std::size_t k = 0; k + 1 < grid.size(); ++k) {
    s[k + 1] = s[k] + arc_length(path, grid[k], grid[k + 1], 1);
  }
  const double total = s.back();
  std::vector<double> out{grid.front()};
  for (std::size_t k = 0; k + 1 < grid.size(); ++k) {
    const bool near_end = s[k] < length || s[k + 1] > total - length;
    const std::size_t n = near_end ? parts : 1;
    for (std::size_t i = 1; i <= n; ++i) {
      out.push_back(i == n ? grid[k + 1] : grid[k] + (grid[k + 1] - grid[k]) * i / n);
    }
  }
  return out;
}

}  // namespace

void LimitRefinementOptions::validate() const {
  if (!(tolerance > 0.0 && tolerance <= 0.5)) {
    throw OptionError("tolerance", shortest_double(tolerance), "must be in (0, 0.5]");
  }
  if (max_rounds < 0) {
    throw OptionError("max_rounds", std::to_string(max_rounds), "must be >= 0 (0 = check only)");
  }
  if (samples < 1) throw OptionError("samples", std::to_string(samples), "must be >= 1");
  if (margin < 1) throw OptionError("margin", std::to_string(margin), "must be >= 1");
}

void FeedratePlannerOptions::validate() const {
  try {
    refinement.validate();
  } catch (const OptionError& e) {
    throw OptionError("refinement." + e.field(), e.value(), e.rule());
  }
  try {
    limits.validate();
  } catch (const OptionError& e) {
    throw OptionError("limits." + e.field(), e.value(), e.rule());
  }
  try {
    regularity.validate();
  } catch (const OptionError& e) {
    throw OptionError("regularity." + e.field(), e.value(), e.rule());
  }
  if (!(grid_spacing > 0.0 && std::isfinite(grid_spacing))) {
    throw OptionError("grid_spacing", std::to_string(grid_spacing), "must be > 0 and finite");
  }
  if (!(end_refinement_length >= 0.0 && std::isfinite(end_refinement_length))) {
    throw OptionError("end_refinement_length", std::to_string(end_refinement_length),
                      "must be >= 0 and finite");
  }
  if (end_refinement < 1) {
    throw OptionError("end_refinement", std::to_string(end_refinement), "must be >= 1");
  }
  // The refined start must lie inside the first window's committed part, so
  // that every overlap consists of full-length intervals (checked below).
  const double refined_intervals =
      static_cast<double>(end_refinement) * std::ceil(end_refinement_length / grid_spacing);
  if (end_refinement > 1 && refined_intervals > static_cast<double>(commit_intervals)) {
    throw OptionError("end_refinement", std::to_string(end_refinement),
                      "end_refinement * ceil(end_refinement_length / grid_spacing) must be <= "
                      "commit_intervals");
  }
  if (window_intervals < 2) {
    throw OptionError("window_intervals", std::to_string(window_intervals), "must be >= 2");
  }
  if (commit_intervals < 1 || commit_intervals >= window_intervals) {
    throw OptionError("commit_intervals", std::to_string(commit_intervals),
                      "must be in [1, window_intervals - 1]");
  }
  // The overlap must hold a full stop from the largest path speed, else the
  // rest condition at a window's end slows the part that is kept: the
  // straight-line S-curve stopping distance v^2/(2a) + v a/(2j), with the
  // path limits in direction (cos t, sin t) v = min_i V_i/|d_i| (a, j alike),
  // maximised over t (curvature only lowers the speeds).
  double braking = 0.0;
  for (int step = 0; step < 360; ++step) {
    const double t = step * std::numbers::pi / 720.0;  // [0, pi/2): |d_i| symmetric
    const double d[2] = {std::cos(t), std::sin(t)};
    double v = INFINITY, a = INFINITY, j = INFINITY;
    for (int i = 0; i < 2; ++i) {
      if (d[i] <= 0.0) continue;
      v = std::min(v, limits.axes[i].velocity / d[i]);
      a = std::min(a, limits.axes[i].acceleration / d[i]);
      j = std::min(j, limits.axes[i].jerk / d[i]);
    }
    braking = std::max(braking, v * v / (2 * a) + v * a / (2 * j));
  }
  const double overlap = static_cast<double>(window_intervals - commit_intervals) * grid_spacing;
  if (overlap < braking) {
    std::ostringstream m;
    m << "overlap (window_intervals - commit_intervals) * grid_spacing = " << overlap
      << " mm must be >= the stopping distance " << braking << " mm at these limits";
    throw OptionError("commit_intervals", std::to_string(commit_intervals), m.str());
  }
  try {
    speed_cap.validate();
  } catch (const OptionError& e) {
    throw OptionError("speed_cap." + e.field(), e.value(), e.rule());
  }
  if (!(tolerance > 0.0)) throw OptionError("tolerance", std::to_string(tolerance), "must be > 0");
  if (max_iterations < 1) {
    throw OptionError("max_iterations", std::to_string(max_iterations), "must be >= 1");
  }
}

namespace {

// The overlapping windows (feedrate_planner.hpp): plan.x over the whole
// path, one WindowRecord per window.
std::vector<WindowRecord> plan_windows(const FeedratePlannerOptions& options, WindowSolver& solver,
                                       ScaledPlan& plan, const ProgressCallback& progress) {
  const std::size_t N = plan.grid.size() - 1;
  const std::size_t n_windows =
      N <= options.window_intervals
          ? 1
          : 1 + (N - options.window_intervals + options.commit_intervals - 1) /
                    options.commit_intervals;
  std::vector<WindowRecord> records;
  plan.x.assign({0.0, 0.0});  // v, a at rest at node 0
  WindowState state;
  std::vector<double> overlap;  // previous solution from the new window's start on
  for (std::size_t first = 0;;) {
    const std::size_t last = std::min(first + options.window_intervals, N);
    const bool final_window = last == N;
    std::vector<feedrate_detail::NodeCoefficients> nodes(plan.nodes.begin() + first,
                                                         plan.nodes.begin() + last + 1);
    std::ostringstream where;
    where << "window " << records.size() + 1 << " of " << n_windows << " (grid nodes " << first
          << ".." << last << ", path parameter u in [" << plan.grid[first] << ", "
          << plan.grid[last] << "])";
    std::vector<double> guess = initial_guess(nodes, state, overlap);
    const WindowSolution s =
        solver.solve(std::move(nodes), state, std::move(guess), {}, where.str());
    const std::vector<double>& x = s.x;
    const std::size_t keep = final_window ? last - first : options.commit_intervals;
    // Intervals 0..keep-1 and nodes 1..keep (node 0 is the previous end).
    plan.x.insert(plan.x.end(), x.begin() + 2, x.begin() + 4 * keep + 2);
    records.push_back({first, last, keep, s.iterations, s.seconds});
    if (progress) progress("plan feedrate (windows)", records.size(), n_windows);
    if (final_window) break;
    state = {x[4 * keep], x[4 * keep + 1]};
    overlap.assign(x.begin() + 4 * keep, x.end());
    first += keep;
  }
  return records;
}

}  // namespace

FeedrateProfile plan_feedrate(const PlanarPath& path, const FeedratePlannerOptions& options,
                              const ProgressCallback& progress) {
  options.validate();
  check_regular_path(path, options.regularity);
  const Scaling scaling = Scaling::for_path(path, options.limits);
  ScaledPlan plan;
  plan.grid = refine_ends(path, arc_length_grid(path, options.grid_spacing, 2),
                          options.end_refinement_length, options.end_refinement);
  plan.nodes.resize(plan.grid.size());
  for (std::size_t k = 0; k < plan.grid.size(); ++k) {
    plan.nodes[k] =
        feedrate_detail::node_coefficients(path.evaluate(plan.grid[k]), plan.grid[k], scaling,
                                           options.limits, options.speed_cap.at(plan.grid[k]));
  }
  WindowSolver solver(options);
  const std::vector<WindowRecord> windows = plan_windows(options, solver, plan, progress);
  const LimitRefinementSummary refinement =
      feedrate_detail::refine_limits(path, options, scaling, solver, plan);
  FeedrateProfile profile = feedrate_detail::to_profile(plan, scaling);
  profile.windows = windows;
  profile.refinement = refinement;
  return profile;
}

}  // namespace cnclab
