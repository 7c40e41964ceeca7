// A piece of a path (PathPiece), the parameter at an arc length on a circle
// (closed form s = r * angle), and references of consecutive pieces planned
// from rest joined in time (concatenate_references): continuous time and
// position, the machine at rest at every joint.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/reference_trajectory.hpp"

namespace cnclab {
namespace {

// A quarter circle of radius 20 mm: u in [0, 1] sweeps pi/2, s = 10 pi u.
const CirclePath& quarter() {
  static const CirclePath c(Vec2(0, 0), 20.0, 0.0, std::numbers::pi / 2);
  return c;
}

TEST(PathPiece, ParameterAtArcLengthOnACircle) {
  const double total = 10.0 * std::numbers::pi;
  for (const double s : {0.0, 1.0, 7.5, 20.0, total}) {
    EXPECT_NEAR(parameter_at_arc_length(quarter(), s), s / total, 1e-9) << s;
  }
  const PathPiece piece(quarter(), 0.25, 0.5);
  EXPECT_EQ(piece.u_begin(), 0.25);
  EXPECT_EQ(piece.u_end(), 0.5);
  EXPECT_EQ(piece.evaluate(0.3).position, quarter().evaluate(0.3).position);
  EXPECT_NEAR(arc_length(piece), total / 4, 1e-9);
}

TEST(PathPiece, ConcatenatedPiecesStopAtTheirJoint) {
  const PathPiece first(quarter(), 0.0, 0.5), second(quarter(), 0.5, 1.0);
  const ReferenceTrajectory a = interpolate(first, plan_feedrate(first));
  const ReferenceTrajectory b = interpolate(second, plan_feedrate(second));
  const ReferenceTrajectory r = concatenate_references({a, b});
  ASSERT_EQ(r.samples(), a.samples() + b.samples());
  const Eigen::Index j = a.samples();  // the second piece's first sample
  for (Eigen::Index k = 1; k < r.samples(); ++k) {
    ASSERT_NEAR(r.time[static_cast<std::size_t>(k)] - r.time[static_cast<std::size_t>(k - 1)],
                r.period, 1e-12)
        << k;
  }
  EXPECT_LT((r.position.row(j) - r.position.row(j - 1)).norm(), 1e-9);
  EXPECT_LT(r.velocity.row(j - 1).norm(), 1e-9);
  EXPECT_LT(r.velocity.row(j).norm(), 1e-9);
  EXPECT_EQ(r.u[static_cast<std::size_t>(j)], b.u.front());
  EXPECT_EQ(r.position.bottomRows(b.samples()), b.position);
  ReferenceTrajectory other = b;
  other.period = 2e-3;
  EXPECT_THROW(concatenate_references({a, other}), Error);
  EXPECT_THROW(concatenate_references({}), Error);
}

}  // namespace
}  // namespace cnclab
