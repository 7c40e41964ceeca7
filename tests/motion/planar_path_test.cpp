#include "cnclab/motion/planar_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/path_grid.hpp"

namespace cnclab {
namespace {

TEST(PlanarPath, DerivativesMatchFiniteDifferences) {
  const CirclePath circle(Vec2(1, 2), 7.0, 0.2, -3.0);
  const CubicBezierPath bezier({Vec2(0, 0), Vec2(60, 80), Vec2(120, -60), Vec2(180, 20)});
  const EpitrochoidPath trochoid(Vec2(0, 0), 100, 8, 7, 1);
  for (const PlanarPath* path :
       {static_cast<const PlanarPath*>(&circle), static_cast<const PlanarPath*>(&bezier),
        static_cast<const PlanarPath*>(&trochoid)}) {
    const double h = 1e-5 * (path->u_end() - path->u_begin());
    for (const double f : {0.1, 0.5, 0.9}) {
      const double u = path->u_begin() + f * (path->u_end() - path->u_begin());
      const PathPoint p = path->evaluate(u), a = path->evaluate(u + h), b = path->evaluate(u - h);
      const double scale = 1.0 + p.d1.norm();
      EXPECT_LT(((a.position - b.position) / (2 * h) - p.d1).norm(), 1e-6 * scale);
      EXPECT_LT(((a.d1 - b.d1) / (2 * h) - p.d2).norm(), 1e-6 * (1.0 + p.d2.norm()));
      EXPECT_LT(((a.d2 - b.d2) / (2 * h) - p.d3).norm(), 1e-6 * (1.0 + p.d3.norm()));
    }
  }
}

TEST(PlanarPath, ArcLengthAndEqualArcGrid) {
  const CirclePath circle(Vec2(0, 0), 10.0, 0.0, 2 * std::numbers::pi);
  EXPECT_NEAR(arc_length(circle), 20 * std::numbers::pi, 1e-10);
  // On a circle equal arcs are equal parameter steps.
  const std::vector<double> grid = arc_length_grid(circle, 1.0);
  ASSERT_EQ(grid.size(), 64u);  // ceil(62.83) = 63 intervals
  for (std::size_t k = 0; k < grid.size(); ++k) EXPECT_NEAR(grid[k], k / 63.0, 1e-9);
  // On a Bezier curve the arcs between nodes are equal to the table's accuracy.
  const CubicBezierPath bezier({Vec2(0, 0), Vec2(60, 80), Vec2(120, -60), Vec2(180, 20)});
  const std::vector<double> g = arc_length_grid(bezier, 2.0);
  const double step = arc_length(bezier) / (g.size() - 1);
  for (std::size_t k = 0; k + 1 < g.size(); ++k) {
    EXPECT_NEAR(arc_length(bezier, g[k], g[k + 1], 8), step, 1e-3 * step) << k;
  }
  EXPECT_THROW(arc_length_grid(bezier, 0.0), Error);
}

TEST(PlanarPath, RegularPathsPassTheCuspCheck) {
  EXPECT_NO_THROW(check_regular_path(EpitrochoidPath(Vec2(0, 0), 100, 8, 7, 2)));
  // R1 = k R2: a cusp where |C'| = |R1 - k R2| = 0, at u = pi / (k - 1) (mod 2 pi / (k - 1)).
  try {
    check_regular_path(EpitrochoidPath(Vec2(0, 0), 70, 10, 7, 1));
    ADD_FAILURE() << "expected a cusp error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("cusp"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cnclab
