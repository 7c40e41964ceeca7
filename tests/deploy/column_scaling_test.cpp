// A narx model's physical columns map to the following_error dataset's
// stored values bit for bit: ColumnScaling repeats the generator's own
// arithmetic (data/following_error.hpp), which this checks against it.
#include <gtest/gtest.h>

#include "cnclab/core/rng.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/deploy/deployed_model.hpp"

namespace cnclab {
namespace {

TEST(ColumnScaling, IsTheGeneratorsMapminmaxBitForBit) {
  Rng rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::VectorXd x(500);
    const double scale = std::pow(10.0, 6.0 * (rng.uniform() - 0.5));
    for (Eigen::Index i = 0; i < x.size(); ++i) x[i] = (rng.uniform() - 0.3) * scale;
    ColumnRange range;
    const Eigen::VectorXd y = normalise_minmax(x, "x", &range);
    const ColumnScaling c{"x", "mm", range.min, range.max};
    for (Eigen::Index i = 0; i < x.size(); ++i) {
      EXPECT_EQ(c.to_dataset(x[i]), y[i]);
      EXPECT_EQ(c.to_physical(y[i]), to_physical(y[i], range));
    }
  }
}

}  // namespace
}  // namespace cnclab
