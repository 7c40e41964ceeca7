// The direction features of a commanded velocity against their definitions
// worked out by hand on a short series (motion/axis_direction.hpp): sign
// with its deadband, the direction held through standstill, and the
// reversal pulse d exp(-(t - t_c) / tau) restarting at each change, and
// t - t_c itself.
#include "cnclab/motion/axis_direction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

TEST(AxisDirection, FeaturesOfAHandSeries) {
  AxisDirectionOptions o;
  o.deadband = 0.01;
  o.reversal_time_constant = 0.004;  // 4 ticks
  o.period = 1e-3;
  // rest, a move +x, standstill inside the deadband, back -x, rest.
  const std::vector<double> v = {0, 0, 5, 7, 0.005, 0, -3, -4, -0.002, 0};
  const std::vector<double> sign = {0, 0, 1, 1, 0, 0, -1, -1, 0, 0};
  const std::vector<double> dir = {0, 0, 1, 1, 1, 1, -1, -1, -1, -1};
  // Ticks since the last change of direction: at 2 (0 -> +1) and 6 (+1 -> -1).
  const std::vector<double> since = {0, 0, 0, 1, 2, 3, 0, 1, 2, 3};
  const auto f = axis_direction_series(
      v, {AxisFeature::sign, AxisFeature::direction, AxisFeature::reversal}, o);
  for (std::size_t t = 0; t < v.size(); ++t) {
    EXPECT_EQ(f[0][t], sign[t]) << t;
    EXPECT_EQ(f[1][t], dir[t]) << t;
    EXPECT_NEAR(f[2][t], dir[t] * std::exp(-since[t] * 1e-3 / 0.004), 1e-15) << t;
  }
  // The time since the change itself: infinity before the first motion.
  AxisDirection a(o);
  for (std::size_t t = 0; t < v.size(); ++t) {
    a.step(v[t]);
    EXPECT_EQ(a.since_change(), t < 2 ? INFINITY : since[t] * 1e-3) << t;
  }
  a.reset();
  EXPECT_EQ(a.since_change(), INFINITY);
}

TEST(AxisDirection, ResetForgetsAndNonFiniteIsStandstill) {
  AxisDirection a;
  a.step(2.0);
  EXPECT_EQ(a.direction(), 1.0);
  a.step(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(a.sign(), 0.0);
  EXPECT_EQ(a.direction(), 1.0);
  a.reset();
  EXPECT_EQ(a.direction(), 0.0);
  EXPECT_EQ(a.reversal(), 0.0);
  // Long after a change the pulse is exactly 0 (flushed, no denormals).
  a.step(1.0);
  for (int t = 0; t < 20000; ++t) a.step(1.0);
  EXPECT_EQ(a.reversal(), 0.0);
  EXPECT_EQ(a.direction(), 1.0);
}

TEST(AxisDirection, NamesRoundTripAndBadOptionsNameTheField) {
  for (const AxisFeature f : {AxisFeature::sign, AxisFeature::direction, AxisFeature::reversal}) {
    AxisFeature back{};
    ASSERT_TRUE(parse_axis_feature(to_string(f), back));
    EXPECT_EQ(back, f);
  }
  AxisFeature none{};
  EXPECT_FALSE(parse_axis_feature("velocity", none));
  AxisDirectionOptions o;
  o.reversal_time_constant = 0;
  try {
    AxisDirection bad(o);
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "reversal_time_constant");
  }
}

}  // namespace
}  // namespace cnclab
