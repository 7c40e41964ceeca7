// Limit refinement benchmark (docs/motion.md): plans the seed 002 study's tool path
// (the following_error generator's random NURBS walk with the study's options
// and dataset seed, configs/studies/contour_error.yaml) without and with the
// limit refinement, and prints, for both, the traversal time, the planning
// time and the peak per-axis |v|, |a|, |j| of the 1 ms reference by forward
// differences of its positions (first, second, third differences: positive
// weighted averages of the true derivatives), divided by the limits.
// Usage: cnclab_bench_motion_limits [CONTROL_POINTS [SEED [MARGIN]]]   (default 1450 2002, the
//        refinement's default margin)
//        cnclab_bench_motion_limits --cusp   (the near-cusp Bézier of the tests)
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

#include "cnclab/core/rng.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/data/nurbs_path.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"

namespace {

using namespace cnclab;

// Peak |forward difference| / limit: v, a, j for x, y; and the number of
// samples whose jerk difference exceeds the limit by more than 0.5 %.
struct DifferenceRatios {
  std::array<double, 2> v{}, a{}, j{};
  long jerk_over = 0;
  double worst() const { return std::max({v[0], v[1], a[0], a[1], j[0], j[1]}); }
};

DifferenceRatios difference_ratios(const ReferenceTrajectory& r, const PlanarLimits& limits) {
  const Eigen::MatrixX2d& p = r.position;
  const double h = r.period;
  DifferenceRatios out;
  for (Eigen::Index k = 0; k + 3 < r.samples(); ++k) {
    bool over = false;
    for (int i = 0; i < 2; ++i) {
      const AxisLimits& L = limits.axes[static_cast<std::size_t>(i)];
      const double p0 = p(k, i), p1 = p(k + 1, i), p2 = p(k + 2, i), p3 = p(k + 3, i);
      const double j = std::abs(p3 - 3 * p2 + 3 * p1 - p0) / (h * h * h) / L.jerk;
      out.v[i] = std::max(out.v[i], std::abs(p1 - p0) / h / L.velocity);
      out.a[i] = std::max(out.a[i], std::abs(p2 - 2 * p1 + p0) / (h * h) / L.acceleration);
      out.j[i] = std::max(out.j[i], j);
      over = over || j > 1.005;
    }
    out.jerk_over += over;
  }
  return out;
}

struct Result {
  FeedrateProfile profile;
  double seconds = 0.0;
  DifferenceRatios ratios;
};

Result plan(const PlanarPath& path, const FeedratePlannerOptions& options) {
  Result r;
  const auto t0 = std::chrono::steady_clock::now();
  r.profile = plan_feedrate(path, options);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.ratios = difference_ratios(interpolate(path, r.profile, 1e-3), options.limits);
  return r;
}

void print(const char* name, const Result& r) {
  const DifferenceRatios& d = r.ratios;
  std::printf("%-10s %10.4f s %9.1f s   %.4f %.4f   %.4f %.4f   %.4f %.4f %8ld\n", name,
              r.profile.total_time(), r.seconds, d.v[0], d.v[1], d.a[0], d.a[1], d.j[0], d.j[1],
              d.jerk_over);
}

}  // namespace

int main(int argc, char** argv) {
  const FollowingErrorOptions study;
  std::unique_ptr<PlanarPath> path;
  if (argc > 1 && std::string(argv[1]) == "--cusp") {
    path = std::make_unique<CubicBezierPath>(
        std::array<Vec2, 4>{Vec2(0, 0), Vec2(30, 30), Vec2(8, 30), Vec2(30, 0)});
    std::printf("path: near-cusp cubic Bezier (0,0) (30,30) (8,30) (30,0), 0.195 mm turn\n");
  } else {
    RandomNurbsPathOptions o = study.path;
    if (argc > 1) o.control_points = static_cast<std::size_t>(std::atol(argv[1]));
    const long seed = argc > 2 ? std::atol(argv[2]) : 2002;
    Rng rng(static_cast<std::uint64_t>(seed));
    path = std::make_unique<NurbsPlanarPath>(random_planar_nurbs(o, rng));
    std::printf("path: following_error generator's random NURBS, %zu control points, seed %ld\n",
                o.control_points, seed);
  }
  FeedratePlannerOptions refined = study.planner;
  if (argc > 3) refined.refinement.margin = static_cast<std::size_t>(std::atol(argv[3]));
  FeedratePlannerOptions off = study.planner;
  off.refinement.max_rounds = 0;
  const Result before = plan(*path, off);
  const Result after = plan(*path, refined);
  std::printf("\n%-10s %12s %11s   %-13s   %-13s   %-13s %8s\n", "plan", "traversal", "planning",
              "|v|/V x y", "|a|/A x y", "|j|/J x y", "j > 1.005");
  print("unrefined", before);
  print("refined", after);
  const LimitRefinementSummary& s = after.profile.refinement;
  std::printf(
      "\nrefinement (margin %zu): %d rounds, %zu intervals bisected, %zu local solves (%zu "
      "widened, %d Ipopt iterations), %.2f s (checks and local solves); converged: %s\n",
      refined.refinement.margin, s.rounds, s.bisected, s.local_solves, s.widened,
      s.local_iterations, s.seconds, s.converged ? "yes" : "no");
  std::printf("checked peak ratio (9 instants per interval): %.4f before, %.4f after\n",
              s.initial.worst(), s.final.worst());
  std::printf("traversal-time cost: %+.4f %%  (%.4f s -> %.4f s)\n",
              100 * (after.profile.total_time() / before.profile.total_time() - 1),
              before.profile.total_time(), after.profile.total_time());
  return 0;
}
