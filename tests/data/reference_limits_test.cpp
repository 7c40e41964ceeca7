// Limit refinement (docs/motion.md) on seed 002's kind of path: the 1 ms reference of the random
// NURBS tool path, and of the following_error generator's output, holds v, a and j per axis within
// 0.5 %, checked by forward differences of the sampled positions
// (tests/motion/difference_peaks.hpp: a difference is a positive weighted average of the true
// derivative, so it is an independent lower bound of the true peak).
#include <gtest/gtest.h>

#include <cstdio>

#include "cnclab/core/config.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/data/nurbs_path.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "motion/difference_peaks.hpp"

namespace cnclab {
namespace {

using testing::difference_peaks;
using testing::DifferencePeaks;

constexpr double kTolerance = 0.005;  // docs/motion.md: every limit within 0.5 %
constexpr std::size_t kControlPoints = 30;
constexpr int kSeed = 2;

void expect_within_limits(const DifferencePeaks& p, const PlanarLimits& limits, const char* what) {
  std::printf("%s: peak / limit  v %.4f %.4f  a %.4f %.4f  j %.4f %.4f\n", what,
              p.v[0] / limits.axes[0].velocity, p.v[1] / limits.axes[1].velocity,
              p.a[0] / limits.axes[0].acceleration, p.a[1] / limits.axes[1].acceleration,
              p.j[0] / limits.axes[0].jerk, p.j[1] / limits.axes[1].jerk);
  for (int i = 0; i < 2; ++i) {
    const AxisLimits& L = limits.axes[static_cast<std::size_t>(i)];
    EXPECT_LE(p.v[i], L.velocity * (1 + kTolerance)) << what << ", axis " << i;
    EXPECT_LE(p.a[i], L.acceleration * (1 + kTolerance)) << what << ", axis " << i;
    EXPECT_LE(p.j[i], L.jerk * (1 + kTolerance)) << what << ", axis " << i;
  }
}

// The generator's path construction and planner options (the study's:
// configs/datasets/following_error_seed002.yaml uses the defaults), a shorter walk. The
// seed is one whose unrefined plan exceeds the jerk limit between nodes
// (the assertion on the summary below keeps the test from going vacuous).
TEST(ReferenceLimits, RandomNurbsPathHoldsEveryLimitByDifferences) {
  const FollowingErrorOptions study;
  RandomNurbsPathOptions path_options = study.path;
  path_options.control_points = kControlPoints;
  Rng rng(kSeed);
  const NurbsPlanarPath path(random_planar_nurbs(path_options, rng));
  const FeedrateProfile profile = plan_feedrate(path, study.planner);
  const LimitRefinementSummary& s = profile.refinement;
  std::printf(
      "%zu control points, seed %d: %.3f s -> %.3f s (%+.3f %%), worst checked ratio "
      "%.4f -> %.4f, %d rounds, %zu local solves\n",
      path_options.control_points, kSeed, s.initial_time, profile.total_time(),
      100 * (profile.total_time() / s.initial_time - 1), s.initial.worst(), s.final.worst(),
      s.rounds, s.local_solves);
  EXPECT_GT(s.initial.worst(), 1 + kTolerance);
  const ReferenceTrajectory r = interpolate(path, profile, 1e-3);
  expect_within_limits(difference_peaks(r.position, r.period), study.planner.limits,
                       "random NURBS path");
}

// The generator's own output: its ref_x, ref_y columns (the 1 ms reference
// positions), with the study's quick profile path (40 control points,
// experiments/contour_error/narx.yaml) and seed, the whole run kept.
TEST(ReferenceLimits, FollowingErrorDatasetReferenceHoldsEveryLimit) {
  const ConfigDocument doc = ConfigDocument::parse(
      "dataset:\n  generator: following_error\n  options:\n"
      "    path: {control_points: 40}\n    runs: 1\n    samples: 0\n",
      "test.yaml");
  const auto generator = read_generator(doc.root().section("dataset"));
  Rng rng(2002);
  const Dataset d = generator->generate(rng);
  Eigen::MatrixX2d position(static_cast<Eigen::Index>(d.num_samples()), 2);
  position.col(0) = d.metadata.row(d.metadata_row("ref_x")).transpose();
  position.col(1) = d.metadata.row(d.metadata_row("ref_y")).transpose();
  const double period = d.metadata(d.metadata_row("time"), 1);
  ASSERT_NEAR(period, 1e-3, 1e-12);
  expect_within_limits(difference_peaks(position, period), FollowingErrorOptions{}.planner.limits,
                       "following_error dataset");
}

}  // namespace
}  // namespace cnclab
