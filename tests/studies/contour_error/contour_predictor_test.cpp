// The contour predictor on a circle: its following errors are the per-axis
// predictors', its contour value is Eqs. 3-6 (taylor_contour_error) at the
// predicted tool position, which on a circle is within the Taylor
// estimate's bound of the exact ||P - c| - r|.
#include "cnclab/studies/contour_error/contour_predictor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "common/stable_narx.hpp"

namespace cnclab {
namespace {

using testing::stable_narx_model;

constexpr double kPi = std::numbers::pi;

NarxOptions paper_architecture() {
  NarxOptions o;  // seed 002: 4 input and 4 feedback delays, 12 tanh neurons
  o.input_delays = 4;
  o.feedback_delays = 4;
  o.hidden = 12;
  return o;
}

// A circle of radius r traversed at a varying feed: u(t) on [0, 1], the
// interpolator's C(u), C'(u), C''(u) and the axis velocity C'(u) u'.
struct CircleTick {
  Vec2 velocity;
  PathPoint reference;
  Vec2 acceleration;  // q'' = C'' u'^2 + C' u''
};
CircleTick circle_tick(const CirclePath& c, Eigen::Index k, Eigen::Index n) {
  const double s = static_cast<double>(k) / static_cast<double>(n);  // t / T
  const double period = static_cast<double>(n) * 1e-3;               // T [s]
  // u = s - 0.05 sin(2 pi s) / (2 pi): u' = (1 - 0.05 cos(2 pi s)) / T > 0.
  const double u = s - 0.05 * std::sin(2 * kPi * s) / (2 * kPi);
  const double du = (1.0 - 0.05 * std::cos(2 * kPi * s)) / period;
  const double ddu = 0.1 * kPi * std::sin(2 * kPi * s) / (period * period);
  CircleTick tick;
  tick.reference = c.evaluate(u);
  tick.velocity = tick.reference.d1 * du;
  tick.acceleration = tick.reference.d2 * du * du + tick.reference.d1 * ddu;
  return tick;
}

TEST(ContourPredictor, TaylorContourOfThePerAxisPredictions) {
  const CirclePath circle(Vec2(150, 120), 25.0, 0.3, 2 * kPi);  // 157 mm in 1.5 s: ~105 mm/s
  const NarxAxisModel mx = stable_narx_model(paper_architecture(), 31);
  const NarxAxisModel my = stable_narx_model(paper_architecture(), 32);
  ContourPredictor predictor(mx, my);
  NarxPredictor alone_x(mx), alone_y(my);
  const Eigen::Index n = 1500;
  double max_error = 0, max_contour = 0;
  for (Eigen::Index k = 0; k <= n; ++k) {
    const CircleTick tick = circle_tick(circle, k, n);
    ContourPrediction out;
    ASSERT_EQ(predictor.step(tick.velocity, tick.reference, out), PredictorStatus::ok);
    double ex = 0, ey = 0;
    alone_x.step(tick.velocity.x(), ex);
    alone_y.step(tick.velocity.y(), ey);
    ASSERT_EQ(out.following_error, Vec2(ex, ey)) << "k " << k;
    ASSERT_EQ(out.actual, tick.reference.position - out.following_error);
    ASSERT_EQ(out.contour_error, taylor_contour_error(tick.reference, out.actual));
    // Independent: the exact distance to the circle, within the Taylor
    // estimate's error bound a^4 / (8 (r - b)^3) <= |e|^4 / (8 (r - |e|)^3)
    // (contour_error_test.cpp) plus rounding.
    const double r = circle.radius(), e = out.following_error.norm();
    const double exact = std::abs((out.actual - circle.centre()).norm() - r);
    const double bound = std::pow(e, 4) / (8 * std::pow(r - e, 3)) + 1e-12;
    ASSERT_LE(std::abs(std::abs(out.contour_error) - exact), bound) << "k " << k;
    max_error = std::max(max_error, e);
    max_contour = std::max(max_contour, exact);
  }
  EXPECT_GT(max_error, 0.01);  // following errors of tens of um: the check has teeth
  EXPECT_GT(max_contour, 1e-3);
}

// The frame of Eqs. 5-6 from the axis velocity and acceleration q', q''
// (u' > 0) gives the contour value of C', C'' to rounding.
TEST(ContourPredictor, AxisVelocityAndAccelerationGiveTheSameFrame) {
  const CirclePath circle(Vec2(0, 0), 8.0, 0.0, -2 * kPi);  // clockwise
  const NarxAxisModel mx = stable_narx_model(paper_architecture(), 41);
  const NarxAxisModel my = stable_narx_model(paper_architecture(), 42);
  ContourPredictor with_path(mx, my), with_axes(mx, my);
  const Eigen::Index n = 800;
  for (Eigen::Index k = 0; k <= n; ++k) {
    const CircleTick tick = circle_tick(circle, k, n);
    PathPoint axes = tick.reference;
    axes.d1 = tick.velocity;
    axes.d2 = tick.acceleration;
    ContourPrediction a, b;
    ASSERT_EQ(with_path.step(tick.velocity, tick.reference, a), PredictorStatus::ok);
    ASSERT_EQ(with_axes.step(tick.velocity, axes, b), PredictorStatus::ok);
    ASSERT_NEAR(a.contour_error, b.contour_error, 1e-12) << "k " << k;
  }
}

TEST(ContourPredictor, BadTickChangesNothingAndResetRestarts) {
  const CirclePath circle(Vec2(0, 0), 30.0, 0.0, 2 * kPi);
  const NarxAxisModel mx = stable_narx_model(paper_architecture(), 51);
  const NarxAxisModel my = stable_narx_model(paper_architecture(), 52);
  ContourPredictor p(mx, my), reference(mx, my);
  const Eigen::Index n = 600;
  std::vector<ContourPrediction> first;
  for (Eigen::Index k = 0; k <= n; ++k) {
    const CircleTick tick = circle_tick(circle, k, n);
    ContourPrediction out, ref_out;
    ASSERT_EQ(p.step(tick.velocity, tick.reference, out), PredictorStatus::ok);
    reference.step(tick.velocity, tick.reference, ref_out);
    first.push_back(out);
    if (k % 100 != 50) continue;
    // Bad ticks between good ones: statuses, `out` untouched.
    const ContourPrediction kept = out;
    PathPoint nan_point = tick.reference;
    nan_point.d2.x() = std::nan("");
    PathPoint stopped = tick.reference;
    stopped.d1.setZero();
    EXPECT_EQ(p.step(Vec2(std::nan(""), 0), tick.reference, out),
              PredictorStatus::non_finite_input);
    EXPECT_EQ(p.step(tick.velocity, nan_point, out), PredictorStatus::non_finite_input);
    EXPECT_EQ(p.step(tick.velocity, stopped, out), PredictorStatus::undefined_tangent);
    EXPECT_EQ(out.contour_error, kept.contour_error);
    EXPECT_EQ(out.following_error, kept.following_error);
  }
  // The state is the reference predictor's (which saw no bad tick).
  const CircleTick last = circle_tick(circle, n, n);
  ContourPrediction a, b;
  p.step(last.velocity, last.reference, a);
  reference.step(last.velocity, last.reference, b);
  EXPECT_EQ(a.following_error, b.following_error);
  // After reset() the run repeats from standstill.
  p.reset();
  for (Eigen::Index k = 0; k <= n; ++k) {
    const CircleTick tick = circle_tick(circle, k, n);
    ContourPrediction out;
    p.step(tick.velocity, tick.reference, out);
    ASSERT_EQ(out.contour_error, first[static_cast<std::size_t>(k)].contour_error) << "k " << k;
  }
}

}  // namespace
}  // namespace cnclab
