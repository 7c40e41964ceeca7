#include "cnclab/motion/feedrate_refinement.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/limit_check.hpp"

namespace cnclab::feedrate_detail {
namespace {

// Node range [first, last] of one local window and the intervals in it to
// bisect.
struct LocalWindow {
  std::size_t first = 0, last = 0;
  std::vector<std::size_t> split;  // ascending interval indices
};

// Windows of `margin` intervals around every violating interval, merged
// where they overlap or touch, in ascending order.
std::vector<LocalWindow> local_windows(const std::vector<std::size_t>& violating,
                                       std::size_t margin, std::size_t intervals) {
  std::vector<LocalWindow> out;
  for (const std::size_t k : violating) {
    const std::size_t first = k > margin ? k - margin : 0;
    const std::size_t last = std::min(k + 1 + margin, intervals);
    if (!out.empty() && first <= out.back().last) {
      out.back().last = std::max(out.back().last, last);
    } else {
      out.push_back({first, last, {}});
    }
    out.back().split.push_back(k);
  }
  return out;
}

// Time tau in [0, h] (scaled) at which the cubic v tau + a tau^2/2 +
// j tau^3/6, non-decreasing on [0, h] (v >= 0 throughout), reaches dw; by
// bisection (monotone, so it cannot miss; 60 halvings reach double precision).
double time_to(double v, double a, double j, double h, double dw) {
  double lo = 0.0, hi = h;
  for (int it = 0; it < 60; ++it) {
    const double t = 0.5 * (lo + hi);
    (v * t + a * t * t / 2 + j * t * t * t / 6 < dw ? lo : hi) = t;
  }
  return 0.5 * (lo + hi);
}

// The local window's grid, coefficients and starting point: the current plan
// over [first, last] with each interval in `split` cut at its parameter
// midpoint; the new node's state is the current cubic's at the time it
// passes there, so the starting point is the current plan, exactly.
ScaledPlan bisected(const PlanarPath& path, const FeedratePlannerOptions& options,
                    const Scaling& scaling, const ScaledPlan& plan, const LocalWindow& window) {
  const std::vector<double>& x = plan.x;
  ScaledPlan local;
  auto add_node = [&](double u, const NodeCoefficients& c, double v, double a) {
    local.grid.push_back(u);
    local.nodes.push_back(c);
    local.x.push_back(v);
    local.x.push_back(a);
  };
  auto add_interval = [&](double h, double j) {
    local.x.push_back(h);
    local.x.push_back(j);
  };
  add_node(plan.grid[window.first], plan.nodes[window.first], x[4 * window.first],
           x[4 * window.first + 1]);
  auto next_split = window.split.begin();
  for (std::size_t k = window.first; k < window.last; ++k) {
    const double v = x[4 * k], a = x[4 * k + 1], h = x[4 * k + 2], j = x[4 * k + 3];
    if (next_split != window.split.end() && *next_split == k) {
      ++next_split;
      const double u = 0.5 * (plan.grid[k] + plan.grid[k + 1]);
      const NodeCoefficients c =
          node_coefficients(path.evaluate(u), u, scaling, options.limits, options.speed_cap.at(u));
      const double tau = time_to(v, a, j, h, c.w - plan.nodes[k].w);
      add_interval(tau, j);
      add_node(u, c, v + a * tau + j * tau * tau / 2, a + j * tau);
      add_interval(h - tau, j);
    } else {
      add_interval(h, j);
    }
    add_node(plan.grid[k + 1], plan.nodes[k + 1], x[4 * k + 4], x[4 * k + 5]);
  }
  return local;
}

template <class T>
void splice(std::vector<T>& whole, std::size_t first, std::size_t count,
            const std::vector<T>& part) {
  whole.erase(whole.begin() + static_cast<std::ptrdiff_t>(first),
              whole.begin() + static_cast<std::ptrdiff_t>(first + count));
  whole.insert(whole.begin() + static_cast<std::ptrdiff_t>(first), part.begin(), part.end());
}

std::string describe(int round, const ScaledPlan& plan, const LocalWindow& w) {
  std::ostringstream m;
  m << "limit refinement round " << round << ", local window (grid nodes " << w.first << ".."
    << w.last << ", path parameter u in [" << plan.grid[w.first] << ", " << plan.grid[w.last]
    << "])";
  return m.str();
}

// Replans window w of the current plan with its intervals bisected and
// splices the result (grid, nodes, solution, ratios) into the plan. Returns
// the solve's Ipopt iterations; throws cnclab::Error if Ipopt fails.
int replan(const PlanarPath& path, const FeedratePlannerOptions& options, const Scaling& scaling,
           WindowSolver& solver, const LocalWindow& w, int round, ScaledPlan& plan,
           std::vector<LimitRatios>& ratios) {
  ScaledPlan local = bisected(path, options, scaling, plan, w);
  const std::size_t n = w.last;
  const WindowSolution s =
      solver.solve(local.nodes, {plan.x[4 * w.first], plan.x[4 * w.first + 1]}, local.x,
                   {plan.x[4 * n], plan.x[4 * n + 1]}, describe(round, plan, w));
  local.x = s.x;
  const std::vector<LimitRatios> local_ratios = interval_limit_ratios(
      path, to_profile(local, scaling), options.limits, options.refinement.samples);
  splice(plan.grid, w.first, n - w.first + 1, local.grid);
  splice(plan.nodes, w.first, n - w.first + 1, local.nodes);
  splice(plan.x, 4 * w.first, 4 * (n - w.first) + 2, local.x);
  splice(ratios, w.first, n - w.first, local_ratios);
  return std::max(s.iterations, 0);
}

}  // namespace

LimitRefinementSummary refine_limits(const PlanarPath& path, const FeedratePlannerOptions& options,
                                     const Scaling& scaling, WindowSolver& solver,
                                     ScaledPlan& plan) {
  const auto t0 = std::chrono::steady_clock::now();
  const LimitRefinementOptions& o = options.refinement;
  const double bound = 1.0 + o.tolerance;
  // The planner's window overlap holds a full stop (validate()).
  const std::size_t wide = options.window_intervals - options.commit_intervals;
  FeedrateProfile profile = to_profile(plan, scaling);
  std::vector<LimitRatios> ratios = interval_limit_ratios(path, profile, options.limits, o.samples);
  LimitRefinementSummary summary;
  summary.initial = peak_limit_ratios(ratios);
  summary.initial_time = profile.total_time();
  for (;; ++summary.rounds) {
    std::vector<std::size_t> violating;
    for (std::size_t k = 0; k < ratios.size(); ++k) {
      if (ratios[k].worst() > bound) violating.push_back(k);
    }
    if (violating.empty() || summary.rounds == o.max_rounds) break;
    summary.bisected += violating.size();
    const std::vector<LocalWindow> windows = local_windows(violating, o.margin, ratios.size());
    // Last window first: splicing it leaves the indices of the earlier ones.
    for (auto w = windows.rbegin(); w != windows.rend(); ++w) {
      ++summary.local_solves;
      try {
        summary.local_iterations +=
            replan(path, options, scaling, solver, *w, summary.rounds + 1, plan, ratios);
      } catch (const Error&) {
        // A margin too short to slow down in: widen to `wide` (room for a
        // full stop) and solve again; a second failure propagates.
        if (wide <= o.margin) throw;
        LocalWindow widened = *w;
        widened.first = w->first > wide - o.margin ? w->first - (wide - o.margin) : 0;
        widened.last = std::min(w->last + (wide - o.margin), ratios.size());
        ++summary.local_solves;
        ++summary.widened;
        summary.local_iterations +=
            replan(path, options, scaling, solver, widened, summary.rounds + 1, plan, ratios);
      }
    }
  }
  summary.final = peak_limit_ratios(ratios);
  summary.converged = summary.final.worst() <= bound;
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

}  // namespace cnclab::feedrate_detail
