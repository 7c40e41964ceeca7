#pragma once
// The runs behind a following_error dataset (following_error.hpp): the plan
// of the path (one, or pieces planned from rest to rest), its time-scaled
// copies, and their simulated following errors. A piece starts cold: the
// simulated machine from its initial state and the direction features from
// rest, as the feedrate job starts each section it plans, checks and
// predicts.
#include <cstdint>
#include <string>
#include <vector>

#include "cnclab/core/progress.hpp"
#include "cnclab/data/following_error.hpp"

namespace cnclab {

// The plan: the whole path in one piece (seed 002), or with plan_length
// consecutive pieces of about that arc length, each planned on its own.
struct FollowingErrorPlan {
  std::vector<PathPiece> pieces;
  std::vector<FeedrateProfile> profiles;
};
// Plans `path` (options.plan_length; a piece Ipopt does not solve takes the
// next one in and is planned again). `progress` hears of the windows (one
// plan) or the pieces.
FollowingErrorPlan plan_following_error(const FollowingErrorOptions& options,
                                        const NurbsPlanarPath& path,
                                        const ProgressCallback& progress);

// One run of the path at a feed factor: the 1 ms reference of its kept
// samples (pieces one after the other), where each piece begins, and the
// following error [mm] (mean of the simulated runs, smoothed per piece).
struct FollowingErrorRun {
  double factor = 1.0;
  ReferenceTrajectory ref;
  std::vector<Eigen::Index> piece_starts;  // ascending, the first 0
  Eigen::MatrixX2d e;
  Eigen::Index samples() const { return ref.samples(); }
};

// The plan at feed factor f (time_scaled per piece; 1: the plan), kept to
// its first `keep` samples (the pieces after them dropped, the last one cut;
// 0: all). cnclab::Error when the run is shorter than `keep`.
FollowingErrorRun following_error_run(const FollowingErrorPlan& plan, double f, Eigen::Index keep,
                                      double period);

// `options.runs` simulations of every piece of `run` from the machine's
// initial state (noise seed of run k of piece p: the stream
// `<streams>[piece/<p>/]run/<k>` of run_seed; the piece part only with
// plan_length), their mean, the csaps smoothing per piece (p = 1: the
// interpolating spline, whose values are the data). Fills run.e.
void simulate_following_error(const FollowingErrorOptions& options, FollowingErrorRun& run,
                              std::uint64_t run_seed, const std::string& streams,
                              const ProgressCallback& progress);

}  // namespace cnclab
