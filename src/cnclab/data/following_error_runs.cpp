#include "cnclab/data/following_error_runs.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/smoothing_spline.hpp"

namespace cnclab {
namespace {

// The first `n` samples of a reference (the simulation is causal: the ticks
// after the kept ones change nothing).
void keep_first(ReferenceTrajectory& r, Eigen::Index n) {
  r.time.resize(static_cast<std::size_t>(n));
  r.u.resize(static_cast<std::size_t>(n));
  for (Eigen::MatrixX2d* m : {&r.position, &r.velocity, &r.acceleration, &r.jerk}) {
    m->conservativeResize(n, 2);
  }
}

// csaps on the sample index (smoothing_spline.hpp) of one piece's mean error.
Eigen::MatrixX2d smoothed(const Eigen::MatrixX2d& mean, double p) {
  if (p == 1.0) return mean;
  const Eigen::Index n = mean.rows();
  Eigen::VectorXd index(n);
  for (Eigen::Index i = 0; i < n; ++i) index[i] = static_cast<double>(i);
  Eigen::MatrixX2d e(n, 2);
  for (int a = 0; a < 2; ++a) {
    const Eigen::VectorXd raw = mean.col(a);
    e.col(a) = SmoothingSpline::fit(index, raw, p).values();
  }
  return e;
}

}  // namespace

FollowingErrorPlan plan_following_error(const FollowingErrorOptions& o, const NurbsPlanarPath& path,
                                        const ProgressCallback& progress) {
  FollowingErrorPlan plan;
  if (o.plan_length == 0.0) {
    plan.pieces.emplace_back(path, path.u_begin(), path.u_end());
    plan.profiles.push_back(plan_feedrate(path, o.planner, progress));
    return plan;
  }
  const double total = arc_length(path);
  const auto count = static_cast<std::size_t>(std::max(1.0, std::round(total / o.plan_length)));
  std::vector<double> joints = {path.u_begin()};
  for (std::size_t k = 1; k < count; ++k) {
    joints.push_back(
        parameter_at_arc_length(path, total * static_cast<double>(k) / static_cast<double>(count)));
  }
  joints.push_back(path.u_end());
  // Ipopt reports a rest-to-rest piece infeasible now and then (a local
  // failure: stopping is always feasible); such a piece takes the next one
  // in and is planned again.
  for (std::size_t k = 0; k + 1 < joints.size();) {
    for (std::size_t end = k + 1;; ++end) {
      try {
        const PathPiece piece(path, joints[k], joints[end]);
        FeedrateProfile profile = plan_feedrate(piece, o.planner);
        plan.pieces.push_back(piece);
        plan.profiles.push_back(std::move(profile));
        k = end;
        break;
      } catch (const Error&) {
        if (end + 1 == joints.size()) throw;
      }
    }
    if (progress) progress("plan pieces", k, count);
  }
  return plan;
}

FollowingErrorRun following_error_run(const FollowingErrorPlan& plan, double f, Eigen::Index keep,
                                      double period) {
  FollowingErrorRun run;
  run.factor = f;
  std::vector<ReferenceTrajectory> refs;
  Eigen::Index total = 0;
  for (std::size_t k = 0; k < plan.pieces.size() && (keep == 0 || total < keep); ++k) {
    refs.push_back(interpolate(
        plan.pieces[k], f == 1.0 ? plan.profiles[k] : time_scaled(plan.profiles[k], f), period));
    run.piece_starts.push_back(total);
    total += refs.back().samples();
  }
  if (keep > total) {
    std::ostringstream m;
    m << "following_error: the plan at feed factor " << f << " has " << total << " samples < the "
      << keep << " kept; lower samples";
    throw Error(m.str());
  }
  run.ref = refs.size() == 1 ? std::move(refs.front()) : concatenate_references(refs);
  if (keep != 0) keep_first(run.ref, keep);
  return run;
}

void simulate_following_error(const FollowingErrorOptions& o, FollowingErrorRun& run,
                              std::uint64_t run_seed, const std::string& streams,
                              const ProgressCallback& progress) {
  const Eigen::Index n = run.samples();
  run.e.resize(n, 2);
  const std::size_t pieces = run.piece_starts.size();
  for (std::size_t p = 0; p < pieces; ++p) {
    const Eigen::Index first = run.piece_starts[p];
    const Eigen::Index count = (p + 1 < pieces ? run.piece_starts[p + 1] : n) - first;
    ReferenceTrajectory piece;
    if (pieces == 1) {
      piece = run.ref;
    } else {
      piece.period = run.ref.period;
      piece.time.assign(run.ref.time.begin() + first, run.ref.time.begin() + first + count);
      for (double& t : piece.time) t -= run.ref.time[static_cast<std::size_t>(first)];
      piece.u.assign(run.ref.u.begin() + first, run.ref.u.begin() + first + count);
      piece.position = run.ref.position.middleRows(first, count);
      piece.velocity = run.ref.velocity.middleRows(first, count);
      piece.acceleration = run.ref.acceleration.middleRows(first, count);
      piece.jerk = run.ref.jerk.middleRows(first, count);
    }
    const std::string prefix =
        streams + (o.plan_length == 0.0 ? "" : "piece/" + std::to_string(p) + "/");
    Eigen::MatrixX2d mean = Eigen::MatrixX2d::Zero(count, 2);
    for (std::size_t k = 0; k < o.runs; ++k) {
      const MachineResponse r = simulate_machine(
          o.machine, piece, derive_seed(run_seed, prefix + "run/" + std::to_string(k)));
      mean += r.following_error;
      if (progress && pieces == 1) progress("simulate runs", k + 1, o.runs);
    }
    mean /= static_cast<double>(o.runs);
    run.e.middleRows(first, count) = smoothed(mean, o.smoothing);
    if (progress && pieces > 1) progress("simulate pieces", p + 1, pieces);
  }
}

}  // namespace cnclab
