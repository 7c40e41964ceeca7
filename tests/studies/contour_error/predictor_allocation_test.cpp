// The real-time path allocates nothing: this executable interposes glibc's
// malloc family (which operator new and Eigen's aligned_malloc call) with
// counting wrappers around __libc_malloc & co., and counts the heap
// allocations during ticks and resets of the contour predictor. Built
// without sanitizers only (AddressSanitizer owns malloc; tests/CMakeLists).
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <vector>

#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/studies/contour_error/contour_predictor.hpp"
#include "common/stable_narx.hpp"

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace {
std::atomic<long> g_allocations{0};  // test-only instrumentation
}  // namespace

extern "C" {
void* malloc(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(size);
}
void* calloc(std::size_t count, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(count, size);
}
void* realloc(void* p, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  *out = __libc_memalign(alignment, size);
  return *out == nullptr ? 12 /* ENOMEM */ : 0;
}
void free(void* p) {
  __libc_free(p);
}
}

namespace cnclab {
namespace {

long allocations() {
  return g_allocations.load(std::memory_order_relaxed);
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
