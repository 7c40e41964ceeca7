#include "cnclab/data/friedman1.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

TEST(Friedman1, NoiseFreeTargetsEqualTheFormula) {
  Rng rng(3);
  const Dataset d = generate_friedman1({500, 7, 0.0}, rng);
  ASSERT_EQ(d.inputs.rows(), 7);
  for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
    const auto x = d.inputs.col(j);
    const double y = 10 * std::sin(std::numbers::pi * x(0) * x(1)) + 20 * std::pow(x(2) - 0.5, 2) +
                     10 * x(3) + 5 * x(4);
    ASSERT_NEAR(d.targets(0, j), y, 1e-12);
    ASSERT_TRUE((x.array() >= 0).all() && (x.array() < 1).all());
  }
}

TEST(Friedman1, NoiseHasTheConfiguredStd) {
  Rng rng(4);
  constexpr std::size_t kN = 20000;
  const Dataset d = generate_friedman1({kN, 5, 2.0}, rng);
  Eigen::VectorXd residual(kN);
  for (Eigen::Index j = 0; j < d.inputs.cols(); ++j) {
    residual(j) = d.targets(0, j) - friedman1_function(&d.inputs(0, j));
  }
  const double mean = residual.mean();
  const double std = std::sqrt((residual.array() - mean).square().sum() / (kN - 1));
  EXPECT_NEAR(mean, 0.0, 5 * 2.0 / std::sqrt(kN));
  EXPECT_NEAR(std, 2.0, 0.05);
}

TEST(Friedman1, RejectsFewerThanFiveInputs) {
  EXPECT_THROW((Friedman1Options{10, 4, 1.0}.validate()), OptionError);
  EXPECT_THROW((Friedman1Options{10, 5, -1.0}.validate()), OptionError);
}

}  // namespace
}  // namespace cnclab
