#include "cnclab/nn/zscore.hpp"

#include <gtest/gtest.h>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr double kZscoreTol = 1e-12;

TEST(ZScore, TrainingDataGetsMeanZeroAndSampleStdOne) {
  Eigen::MatrixXd x(2, 5);
  x << 1, 2, 3, 4, 10, -5, 0, 5, 10, 15;
  ZScoreNormaliser z;
  z.fit(x);
  // Hand values: feature 0 mean 4, sample variance (9+4+1+0+36)/4 = 12.5.
  EXPECT_NEAR(z.mean()(0), 4.0, kZscoreTol);
  EXPECT_NEAR(z.std()(0), std::sqrt(12.5), kZscoreTol);
  const Eigen::MatrixXd t = z.transform(x);
  for (Eigen::Index i = 0; i < 2; ++i) {
    EXPECT_NEAR(t.row(i).mean(), 0.0, kZscoreTol);
    EXPECT_NEAR(std::sqrt(t.row(i).array().square().sum() / 4.0), 1.0, kZscoreTol);
  }
  EXPECT_TRUE(z.inverse_transform(t).isApprox(x, kZscoreTol));
}

TEST(ZScore, ConstantFeatureMapsToZeroAndIsReported) {
  Eigen::MatrixXd x(2, 3);
  x << 7, 7, 7, 1, 2, 3;
  ZScoreNormaliser z;
  z.fit(x);
  EXPECT_EQ(z.constant_features(), std::vector<Eigen::Index>{0});
  EXPECT_TRUE(z.transform(x).row(0).isZero());
}

TEST(ZScore, RejectsTooFewSamplesAndNonFinite) {
  ZScoreNormaliser z;
  EXPECT_THROW(z.fit(Eigen::MatrixXd::Ones(3, 1)), Error);
  Eigen::MatrixXd x = Eigen::MatrixXd::Ones(2, 4);
  x(1, 2) = std::nan("");
  EXPECT_THROW(z.fit(x), Error);
}

}  // namespace
}  // namespace cnclab
