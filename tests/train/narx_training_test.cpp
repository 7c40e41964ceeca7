#include "cnclab/train/narx_training.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

// A first-order discrete feed-drive-like system the NARX can represent:
//   e(t) = 0.8 e(t-1) + 0.3 v(t) - 0.1 v(t-1)
// excited by filtered noise v(t) = 0.95 v(t-1) + 0.2 n(t).
struct Series {
  Eigen::VectorXd v, e;
};

Series first_order_system(Eigen::Index n, Rng& rng) {
  Series s{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n)};
  for (Eigen::Index t = 1; t < n; ++t) {
    s.v[t] = 0.95 * s.v[t - 1] + 0.2 * rng.normal();
    s.e[t] = 0.8 * s.e[t - 1] + 0.3 * s.v[t] - 0.1 * s.v[t - 1];
  }
  return s;
}

NarxOptions small_narx() {
  NarxOptions o;
  o.input_delays = 2;
  o.feedback_delays = 2;
  o.hidden = 4;
  return o;
}

double rms(const Eigen::VectorXd& x) {
  return std::sqrt(x.squaredNorm() / x.size());
}

TEST(NarxTraining, ClosedLoopObjectiveServesBlocksOfOneSimulation) {
  const Narx narx(small_narx());
  Rng rng(3);
  const Series s = first_order_system(50, rng);
  Eigen::VectorXd w(narx.num_parameters());
  narx.initialise(w, rng);
  NarxClosedLoopObjective objective(narx, s.v, s.e);
  const Eigen::Index n = objective.num_residuals();
  ASSERT_EQ(n, 50 - narx.first_step());
  Eigen::MatrixXd full_jac;
  const Eigen::VectorXd expected = narx.simulate_closed_loop(w, s.v, s.e, &full_jac) - s.e.tail(n);
  Eigen::VectorXd r(n);
  Eigen::MatrixXd jac(n, w.size());
  objective.evaluate(w, 0, n, r, &jac);
  EXPECT_EQ(r, expected);
  EXPECT_EQ(jac, full_jac);
  Eigen::VectorXd block(10);
  Eigen::MatrixXd block_jac(10, w.size());
  objective.evaluate(w, 20, 10, block, &block_jac);
  EXPECT_EQ(block, expected.segment(20, 10));
  EXPECT_EQ(block_jac, full_jac.middleRows(20, 10));
  // New parameters: a new simulation, not the cached one.
  w[0] += 0.5;
  objective.evaluate(w, 0, n, r, nullptr);
  EXPECT_EQ(r, narx.simulate_closed_loop(w, s.v, s.e) - s.e.tail(n));
}

// Windows of H steps (docs/narx_training.md): H = 1 is the series-parallel
// (open-loop) prediction, every window starting from measured states; one
// window at least as long as the series is the whole closed loop; the
// Jacobian of any H agrees with central differences of the residuals.
TEST(NarxTraining, ClosedLoopWindowsSpanOpenLoopToParallel) {
  const Narx narx(small_narx());
  Rng rng(5);
  const Series s = first_order_system(60, rng);
  Eigen::VectorXd w(narx.num_parameters());
  narx.initialise(w, rng);
  const Eigen::Index n = 60 - narx.first_step();
  const auto residuals = [&](Eigen::Index horizon, const Eigen::VectorXd& p,
                             Eigen::MatrixXd* jac = nullptr) {
    NarxClosedLoopObjective objective(narx, s.v, s.e, horizon);
    EXPECT_EQ(objective.num_residuals(), n);
    Eigen::VectorXd r(n);
    if (jac) jac->resize(n, p.size());
    objective.evaluate(p, 0, n, r, jac);
    return r;
  };
  NarxOpenLoopObjective open(narx, s.v, s.e);
  Eigen::VectorXd r_open(n);
  open.evaluate(w, 0, n, r_open, nullptr);
  EXPECT_LT((residuals(1, w) - r_open).cwiseAbs().maxCoeff(), 1e-14);
  EXPECT_EQ(residuals(n, w), residuals(0, w));
  EXPECT_EQ(residuals(n + 100, w), residuals(0, w));
  // A window of 7 steps: the first step of each window is the open-loop
  // prediction, later ones are not.
  const Eigen::VectorXd r7 = residuals(7, w);
  EXPECT_LT(std::abs(r7[14] - r_open[14]), 1e-14);
  EXPECT_GT(std::abs(r7[15] - r_open[15]), 1e-6);
  Eigen::MatrixXd jac;
  residuals(7, w, &jac);
  const double h = 1e-6;
  for (Eigen::Index k = 0; k < w.size(); ++k) {
    Eigen::VectorXd up = w, down = w;
    up[k] += h;
    down[k] -= h;
    const Eigen::VectorXd fd = (residuals(7, up) - residuals(7, down)) / (2 * h);
    EXPECT_LT((jac.col(k) - fd).cwiseAbs().maxCoeff(), 1e-7) << "parameter " << k;
  }
  EXPECT_THROW(NarxClosedLoopObjective(narx, s.v, s.e, -1), Error);
}

// A series of independent sequences (starts): each objective equals the
// concatenation of the objectives of the sequences on their own, residuals
// and Jacobian, open loop and closed loop with and without windows; nothing
// reaches across a start.
TEST(NarxTraining, SequencesAreSeriesOfTheirOwn) {
  const Narx narx(small_narx());
  Rng rng(9);
  const Series a = first_order_system(40, rng), b = first_order_system(35, rng);
  Series ab{Eigen::VectorXd(75), Eigen::VectorXd(75)};
  ab.v << a.v, b.v;
  ab.e << a.e, b.e;
  Eigen::VectorXd w(narx.num_parameters());
  narx.initialise(w, rng);
  const std::vector<Eigen::Index> starts = {40};
  const auto evaluate = [&](ResidualObjective& o) {
    Eigen::VectorXd r(o.num_residuals());
    Eigen::MatrixXd j(o.num_residuals(), w.size());
    o.evaluate(w, 0, o.num_residuals(), r, &j);
    return std::make_pair(r, j);
  };
  // `joined`'s residuals and Jacobian rows are `first`'s, then `second`'s.
  const auto expect_concatenation = [&](ResidualObjective& joined, ResidualObjective& first,
                                        ResidualObjective& second) {
    const auto [r, j] = evaluate(joined);
    const auto [r1, j1] = evaluate(first);
    const auto [r2, j2] = evaluate(second);
    ASSERT_EQ(r.size(), r1.size() + r2.size());
    EXPECT_EQ(r.head(r1.size()), r1);
    EXPECT_EQ(r.tail(r2.size()), r2);
    EXPECT_EQ(j.topRows(r1.size()), j1);
    EXPECT_EQ(j.bottomRows(r2.size()), j2);
  };
  for (const Eigen::Index horizon : {Eigen::Index{0}, Eigen::Index{6}}) {
    SCOPED_TRACE("closed loop, horizon " + std::to_string(horizon));
    NarxClosedLoopObjective joined(narx, ab.v, ab.e, horizon, starts);
    NarxClosedLoopObjective first(narx, a.v, a.e, horizon), second(narx, b.v, b.e, horizon);
    expect_concatenation(joined, first, second);
  }
  {
    SCOPED_TRACE("open loop");
    NarxOpenLoopObjective joined(narx, ab.v, ab.e, starts);
    NarxOpenLoopObjective first(narx, a.v, a.e), second(narx, b.v, b.e);
    expect_concatenation(joined, first, second);
  }
  // A sequence no longer than the delays, or starts out of order, are errors.
  EXPECT_NE(testing::error_message<Error>([&] {
              NarxOpenLoopObjective bad(narx, ab.v, ab.e, {74});
            }).find("sequence 1 [74, 75) has 1 samples"),
            std::string::npos);
  EXPECT_NE(testing::error_message<Error>([&] {
              NarxClosedLoopObjective bad(narx, ab.v, ab.e, 0, {40, 30});
            }).find("start 30 is not after 40"),
            std::string::npos);
}

// Seed 002's two-stage method on measurements with output noise: the
// series-parallel stage fits the noisy fed-back errors (equation-error
// bias), the parallel stage then lowers the closed-loop prediction error on
// fresh validation data (noise-free truth, 4000 steps), and the closed-loop
// prediction stays bounded over the whole horizon.
TEST(NarxTraining, TwoStageLowersTheClosedLoopErrorAndStaysStable) {
  Rng rng(2026);
  Series train = first_order_system(800, rng);
  const Series truth_val = first_order_system(4000, rng);
  for (Eigen::Index t = 0; t < train.e.size(); ++t) train.e[t] += 0.03 * rng.normal();

  const Narx narx(small_narx());
  Eigen::VectorXd w(narx.num_parameters());
  Rng init(7, "init");
  narx.initialise(w, init);
  NarxTrainingOptions o;
  o.open_loop.epochs = 200;
  o.closed_loop.epochs = 100;
  o.run_closed_loop = false;
  const NarxTrainingResult stage1 = train_narx(narx, train.v, train.e, w, o);
  ASSERT_TRUE(stage1.open_loop.has_value());
  EXPECT_FALSE(stage1.closed_loop.has_value());
  const auto closed_loop_error = [&](const Eigen::VectorXd& params) {
    const Eigen::VectorXd p = narx.simulate_closed_loop(params, truth_val.v, truth_val.e);
    return Eigen::VectorXd(p - truth_val.e.tail(p.size()));
  };
  const Eigen::VectorXd err1 = closed_loop_error(w);

  o.run_open_loop = false;
  o.run_closed_loop = true;
  const NarxTrainingResult stage2 = train_narx(narx, train.v, train.e, w, o);
  ASSERT_TRUE(stage2.closed_loop.has_value());
  const Eigen::VectorXd err2 = closed_loop_error(w);
  const double scale = rms(truth_val.e);
  std::printf(
      "closed-loop validation RMS: open-loop only %.5f, two-stage %.5f (signal RMS %.4f); "
      "max |error| %.5f -> %.5f; epochs %zu + %zu\n",
      rms(err1), rms(err2), scale, err1.cwiseAbs().maxCoeff(), err2.cwiseAbs().maxCoeff(),
      stage1.open_loop->history.size(), stage2.closed_loop->history.size());
  EXPECT_LT(rms(err2), rms(err1));
  EXPECT_LT(rms(err2), 0.05 * scale);
  // Stable: the error does not grow along the horizon (last quarter vs all).
  EXPECT_TRUE(err2.allFinite());
  EXPECT_LT(rms(err2.tail(1000)), 2.0 * rms(err2));
}

TEST(NarxTraining, RejectsBadOptions) {
  NarxTrainingOptions o;
  o.closed_loop.mu = -1;
  EXPECT_NE(testing::error_message<OptionError>([&] { o.validate(); }).find("closed_loop.mu"),
            std::string::npos);
  o = {};
  o.run_open_loop = o.run_closed_loop = false;
  EXPECT_NE(testing::error_message<OptionError>([&] { o.validate(); }).find("at least one stage"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab
