#include "cnclab/motion/feedrate_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/feedrate_bounds.hpp"
#include "cnclab/motion/scurve.hpp"

namespace cnclab {
namespace {

constexpr double kSCurveTolerance = 0.005;  // issue 9: within 0.5 %

TEST(FeedratePlanner, StraightLineMatchesSCurve) {
  // Lines along x, at 30 degrees (x axis binds: path limits = axis / cos 30),
  // and short (peak velocity not reached), two of them longer than a window.
  struct Case {
    Vec2 end;
  };
  for (const Vec2& end : {Vec2(200, 0), Vec2(173.2050808, 100), Vec2(15, 0), Vec2(400, 0)}) {
    const LinePath line(Vec2(0, 0), end);
    const double c = std::max(std::abs(end.x()), std::abs(end.y())) / end.norm();
    const double expected = scurve_time(end.norm(), 300 / c, 2000 / c, 50000 / c);
    const FeedrateProfile p = plan_feedrate(line);
    std::printf("line to (%.1f, %.1f): planned %.5f s, S-curve %.5f s, %zu windows\n", end.x(),
                end.y(), p.total_time(), expected, p.windows.size());
    EXPECT_NEAR(p.total_time(), expected, kSCurveTolerance * expected);
  }
}

}  // namespace
}  // namespace cnclab
