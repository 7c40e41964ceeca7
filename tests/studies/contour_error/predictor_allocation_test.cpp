// The real-time path allocates nothing: this executable counts the heap
// allocations (common/counting_malloc.hpp) during ticks and resets of the
// contour predictor. Built without sanitizers only (AddressSanitizer owns
// malloc; tests/CMakeLists).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/studies/contour_error/contour_predictor.hpp"
#include "common/counting_malloc.hpp"
#include "common/stable_narx.hpp"

namespace cnclab {
namespace {

long allocations() {
  return testing::heap_allocations();
}

// Keeps the optimiser from eliding an allocation whose result is unused.
void escape(const void* p) {
  asm volatile("" : : "g"(p) : "memory");
}

// The counter sees what the tick path could use: new, std::vector, Eigen.
TEST(PredictorAllocation, CounterSeesHeapAllocations) {
  long before = allocations();
  auto* p = new double(1.0);
  escape(p);
  delete p;
  EXPECT_GE(allocations() - before, 1);
  before = allocations();
  std::vector<double> v(100, 1.0);
  escape(v.data());
  EXPECT_GE(allocations() - before, 1);
  before = allocations();
  Eigen::VectorXd x = Eigen::VectorXd::Ones(100);
  escape(x.data());
  EXPECT_GE(allocations() - before, 1);
}

TEST(PredictorAllocation, TicksAndResetsDoNotAllocate) {
  NarxOptions o;  // seed 002's 12 neurons, 4 input and 4 feedback delays
  const CirclePath circle(Vec2(100, 100), 40.0, 0.0, 2 * std::numbers::pi);
  std::vector<Vec2> velocity;
  std::vector<PathPoint> reference;
  const int n = 5000;
  for (int k = 0; k <= n; ++k) {
    const double u = static_cast<double>(k) / n;
    reference.push_back(circle.evaluate(u));
    velocity.push_back(reference.back().d1 / (n * 1e-3));
  }
  const long before_construction = allocations();
  ContourPredictor predictor(testing::stable_narx_model(o, 1), testing::stable_narx_model(o, 2));
  EXPECT_GT(allocations(), before_construction);  // construction may allocate

  const std::vector<double> past_v(3, 10.0), past_e(4, 0.01);
  PathPoint bad = reference[0];
  bad.d1.setZero();
  ContourPrediction out;
  double sum = 0;
  const long before = allocations();
  for (int k = 0; k <= n; ++k) {
    if (predictor.step(velocity[static_cast<std::size_t>(k)],
                       reference[static_cast<std::size_t>(k)], out) == PredictorStatus::ok) {
      sum += out.contour_error;
    }
    if (k == n / 2) {
      predictor.reset();
      predictor.axis(0).reset(past_v, past_e);
      predictor.step(velocity[0], bad, out);  // a bad tick: status only
    }
  }
  const long during = allocations() - before;
  EXPECT_EQ(during, 0) << "heap allocations on the tick path";
  EXPECT_TRUE(std::isfinite(sum));
}

}  // namespace
}  // namespace cnclab
