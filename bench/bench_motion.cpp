// Motion benchmark: feedrate planning of a >= 170 s path with
// Ipopt (seconds, iterations per window), the two Ipopt-free bounds, the
// 1 ms interpolation and the feed-drive simulator (axis-seconds per wall
// second, i.e. multiples of real time).
//
// The path is a long epitrochoid-like curve (analytic_paths.hpp, closed form,
// no cusp) or, with --nurbs, a random NURBS path like seed 002's.
// Usage: cnclab_bench_motion [TURNS | --nurbs [CONTROL_POINTS]] [WINDOW COMMIT]
//   default 65 turns (about 172 s); windows: FeedratePlannerOptions' defaults
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "cnclab/core/rng.hpp"
#include "cnclab/data/nurbs_path.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "cnclab/motion/feedrate_bounds.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/machine.hpp"

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace cnclab;
  // --nurbs [CONTROL_POINTS]: seed 002's kind of path instead, a random
  // planar NURBS (data/nurbs_path.hpp, default options, seed 1) with 1450
  // control points: the ~58 m walk the following_error study plans (> 170 s).
  const bool nurbs = argc > 1 && std::string(argv[1]) == "--nurbs";
  std::unique_ptr<PlanarPath> path;
  std::size_t arg = 1;
  if (nurbs) {
    RandomNurbsPathOptions o;
    o.control_points = argc > 2 ? static_cast<std::size_t>(std::atol(argv[2])) : 1450;
    Rng rng(1);
    path = std::make_unique<NurbsPlanarPath>(random_planar_nurbs(o, rng));
    std::printf("path: random planar NURBS, degree %d, %zu control points, seed 1, %.0f mm\n",
                o.degree, o.control_points, arc_length(*path, 200000));
    arg = 3;
  } else {
    const double turns = argc > 1 ? std::atof(argv[1]) : 65.0;
    path = std::make_unique<EpitrochoidPath>(Vec2(0, 0), 100.0, 8.0, 7.0, turns);
    std::printf("path: epitrochoid R1 = 100 mm, R2 = 8 mm, k = 7, %.0f turns, %.0f mm\n", turns,
                arc_length(*path, 200000));
    arg = 2;
  }
  FeedratePlannerOptions options;
  if (argc > static_cast<int>(arg) + 1) {
    options.window_intervals = static_cast<std::size_t>(std::atol(argv[arg]));
    options.commit_intervals = static_cast<std::size_t>(std::atol(argv[arg + 1]));
  }
  std::printf(
      "limits per axis: v %.0f mm/s, a %.0f mm/s^2, j %.0f mm/s^3; grid %.2f mm, "
      "windows of %zu intervals, %zu kept\n",
      options.limits.axes[0].velocity, options.limits.axes[0].acceleration,
      options.limits.axes[0].jerk, options.grid_spacing, options.window_intervals,
      options.commit_intervals);

  auto t0 = std::chrono::steady_clock::now();
  const std::clock_t c0 = std::clock();
  const FeedrateProfile profile = plan_feedrate(*path, options);
  const double plan_seconds = seconds_since(t0);
  const double plan_cpu_seconds = static_cast<double>(std::clock() - c0) / CLOCKS_PER_SEC;
  std::vector<int> iterations;
  double solve_seconds = 0.0;
  for (const auto& w : profile.windows) {
    iterations.push_back(w.iterations);
    solve_seconds += w.seconds;
  }
  std::sort(iterations.begin(), iterations.end());
  const double mean_iterations =
      std::accumulate(iterations.begin(), iterations.end(), 0.0) / iterations.size();

  t0 = std::chrono::steady_clock::now();
  const double lower = velocity_acceleration_time(*path, options.limits);
  const double lower_seconds = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  const ConstantFeedrateProfile upper = constant_feedrate_time(*path, options.limits);
  const double upper_seconds = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  const ReferenceTrajectory reference = interpolate(*path, profile, 1e-3);
  const double interpolation_seconds = seconds_since(t0);

  const MachineOptions machine;
  t0 = std::chrono::steady_clock::now();
  const std::clock_t c1 = std::clock();
  const MachineResponse response = simulate_machine(machine, reference, 1);
  const double simulation_seconds = seconds_since(t0);
  const double simulation_cpu_seconds = static_cast<double>(std::clock() - c1) / CLOCKS_PER_SEC;
  const double axis_seconds = 2.0 * profile.total_time();
  double fe_max = 0.0;
  for (Eigen::Index k = 0; k < response.following_error.rows(); ++k) {
    fe_max = std::max(fe_max, response.following_error.row(k).cwiseAbs().maxCoeff());
  }

  std::printf("\nfeedrate planning (Ipopt %s)\n", "3.11, exact Hessian, MUMPS");
  std::printf("  planned traversal time      %10.2f s  (%ld samples at 1 ms)\n",
              profile.total_time(), static_cast<long>(reference.samples()));
  std::printf("  planning wall time          %10.2f s  (%.2f s inside Ipopt), %.1f x real time\n",
              plan_seconds, solve_seconds, profile.total_time() / plan_seconds);
  std::printf("  planning CPU time           %10.2f s  (wall > CPU when the machine is shared)\n",
              plan_cpu_seconds);
  std::printf("  windows                     %10zu     (%.3f s per window)\n",
              profile.windows.size(), solve_seconds / profile.windows.size());
  std::printf("  Ipopt iterations per window %10.1f     (min %d, median %d, max %d)\n",
              mean_iterations, iterations.front(), iterations[iterations.size() / 2],
              iterations.back());
  std::printf(
      "  bounds without Ipopt: v+a lower %.2f s (%.2f s to compute), constant feedrate "
      "upper %.2f s at %.1f mm/s (%.2f s)\n",
      lower, lower_seconds, upper.time, upper.feedrate, upper_seconds);
  std::printf("  planned / lower bound       %10.4f\n", profile.total_time() / lower);
  std::printf("\n1 ms interpolation            %10.3f s wall\n", interpolation_seconds);
  std::printf("\nfeed-drive simulator (%s, %.0f us integration step)\n", machine.name.c_str(),
              machine.timing.integration_step * 1e6);
  std::printf("  simulated                   %10.1f axis-seconds in %.2f s wall\n", axis_seconds,
              simulation_seconds);
  std::printf("  throughput                  %10.1f axis-seconds per wall second (real time = 1)\n",
              axis_seconds / simulation_seconds);
  std::printf("                              %10.1f axis-seconds per CPU second\n",
              axis_seconds / simulation_cpu_seconds);
  std::printf("  max |following error|       %10.1f um\n", fe_max * 1e3);

  t0 = std::chrono::steady_clock::now();
  const ContourErrorComparison contour =
      compare_contour_estimates(*path, reference, response.actual);
  const double contour_seconds = seconds_since(t0);
  const double exact_max = *std::max_element(contour.exact.begin(), contour.exact.end());
  std::printf(
      "\ncontour error on the simulated run (%ld samples, %.2f s wall incl. exact projection)\n",
      static_cast<long>(reference.samples()), contour_seconds);
  std::printf("  exact (projection)          max %8.3f um\n", exact_max * 1e3);
  std::printf("  |estimate - exact| [um]     %10s %10s\n", "mean", "max");
  const std::pair<const char*, const EstimateDiscrepancy*> rows[] = {
      {"Taylor (Eqs. 3-6)", &contour.taylor},
      {"tangent line", &contour.tangent_line},
      {"osculating circle", &contour.osculating_circle}};
  for (const auto& [label, d] : rows) {
    std::printf("  %-27s %10.4f %10.4f\n", label, d->mean * 1e3, d->max * 1e3);
  }
  return 0;
}
