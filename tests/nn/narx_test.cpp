#include "cnclab/nn/narx.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

Eigen::VectorXd smooth_input(Eigen::Index n, double phase) {
  Eigen::VectorXd v(n);
  for (Eigen::Index t = 0; t < n; ++t) {
    v[t] = 0.7 * std::sin(0.05 * t + phase) + 0.3 * std::sin(0.013 * t * t / (1.0 + 0.01 * t));
  }
  return v;
}

NarxOptions small(std::size_t first_input_delay) {
  NarxOptions o;
  o.input_delays = 3;
  o.feedback_delays = 2;
  o.hidden = 5;
  o.first_input_delay = first_input_delay;
  return o;
}

TEST(Narx, RegressorLayoutFollowsTheDelayConvention) {
  Eigen::VectorXd v(8), e(8);
  for (int t = 0; t < 8; ++t) {
    v[t] = 10 + t;
    e[t] = 100 + t;
  }
  // Eq. 1 with v(t): inputs v(t), v(t-1), v(t-2); first full step t = 2.
  const Narx eq1(small(0));
  EXPECT_EQ(eq1.first_step(), 2);
  const Eigen::MatrixXd x = eq1.open_loop_regressors(v, e);
  ASSERT_EQ(x.cols(), 6);
  EXPECT_EQ(x.col(0), (Eigen::VectorXd(5) << 12, 11, 10, 101, 100).finished());
  // MATLAB narxnet(1:3, 1:2): inputs v(t-1..t-3); first full step t = 3.
  const Narx matlab(small(1));
  EXPECT_EQ(matlab.first_step(), 3);
  EXPECT_EQ(matlab.open_loop_regressors(v, e).col(0),
            (Eigen::VectorXd(5) << 12, 11, 10, 102, 101).finished());
  EXPECT_EQ(eq1.num_parameters(), 5u * 5 + 5 + 5 + 1);
}

// The closed loop is the static network fed with its own outputs: rebuild
// the regressors from the simulated series and evaluate them with Mlp.
TEST(Narx, ClosedLoopFeedsBackItsOwnOutputs) {
  const Narx narx(small(0));
  Rng rng(4);
  Eigen::VectorXd w(narx.num_parameters());
  narx.initialise(w, rng);
  const Eigen::VectorXd v = smooth_input(60, 0.2);
  Eigen::VectorXd e0 = Eigen::VectorXd::Zero(60);
  e0.head(2) << 0.3, -0.1;
  const Eigen::VectorXd sim = narx.simulate_closed_loop(w, v, e0);
  Eigen::VectorXd series = e0;
  series.tail(sim.size()) = sim;
  const Eigen::MatrixXd predicted = narx.mlp().predict(w, narx.open_loop_regressors(v, series));
  ASSERT_EQ(predicted.cols(), sim.size());
  for (Eigen::Index s = 0; s < sim.size(); ++s) EXPECT_NEAR(predicted(0, s), sim[s], 1e-13);
}

// Relative error of column p of the dynamic Jacobian against central
// differences of the closed-loop simulation itself.
double jacobian_column_error(const Narx& narx, const Eigen::VectorXd& w, const Eigen::VectorXd& v,
                             const Eigen::VectorXd& e0, const Eigen::MatrixXd& jac,
                             Eigen::Index p) {
  const double h = 1e-6;
  Eigen::VectorXd plus = w, minus = w;
  plus[p] += h;
  minus[p] -= h;
  const Eigen::VectorXd fd =
      (narx.simulate_closed_loop(plus, v, e0) - narx.simulate_closed_loop(minus, v, e0)) / (2 * h);
  return (jac.col(p) - fd).cwiseAbs().maxCoeff() / (1.0 + fd.cwiseAbs().maxCoeff());
}

// The RTRL Jacobian against central differences of the closed-loop
// simulation itself, for both delay conventions and tanh / sigmoid units.
TEST(Narx, DynamicJacobianMatchesFiniteDifferences) {
  for (std::size_t d0 : {0u, 1u}) {
    for (Activation f : {Activation::tanh, Activation::sigmoid}) {
      NarxOptions o = small(d0);
      o.hidden_activation = f;
      const Narx narx(o);
      Rng rng(11 + d0);
      Eigen::VectorXd w(narx.num_parameters());
      narx.initialise(w, rng);
      w *= 2.0;  // stronger feedback: the recursion matters
      const Eigen::VectorXd v = smooth_input(80, 1.0);
      Eigen::VectorXd e0 = Eigen::VectorXd::Zero(80);
      e0.head(3) << 0.2, -0.4, 0.1;
      Eigen::MatrixXd jac;
      narx.simulate_closed_loop(w, v, e0, &jac);
      double worst = 0.0;
      for (Eigen::Index p = 0; p < w.size(); ++p) {
        worst = std::max(worst, jacobian_column_error(narx, w, v, e0, jac, p));
      }
      EXPECT_LT(worst, 1e-7) << d0 << " " << to_string(f);
      // Not a static Jacobian: feedback makes late rows depend on many steps.
      EXPECT_GT(jac.bottomRows(1).norm(), 0.0);
    }
  }
}

// Over many of the recursion's internal 64-row blocks and a last partial
// one: central differences for a spread of parameters (every kind: input,
// feedback weights, biases, output weights).
TEST(Narx, DynamicJacobianMatchesFiniteDifferencesOverLongSeries) {
  const Narx narx(small(1));
  Rng rng(5);
  Eigen::VectorXd w(narx.num_parameters());
  narx.initialise(w, rng);
  const Eigen::Index n = 700;  // 697 steps: 10 full blocks and one of 57 rows
  const Eigen::VectorXd v = smooth_input(n, 0.4);
  Eigen::VectorXd e0 = Eigen::VectorXd::Zero(n);
  e0.head(3) << 0.1, 0.3, -0.2;
  Eigen::MatrixXd jac;
  narx.simulate_closed_loop(w, v, e0, &jac);
  ASSERT_EQ(jac.rows(), n - narx.first_step());
  for (Eigen::Index p = 0; p < w.size(); p += 3) {
    EXPECT_LT(jacobian_column_error(narx, w, v, e0, jac, p), 1e-7) << "parameter " << p;
  }
}

// Two input channels: each channel's delays together, channel by channel,
// then the fed-back errors; a series with the wrong channel count is an error.
TEST(Narx, RegressorLayoutOfSeveralChannels) {
  NarxOptions o = small(0);
  o.inputs = 2;
  const Narx narx(o);
  Eigen::MatrixXd v(8, 2);
  Eigen::VectorXd e(8);
  for (int t = 0; t < 8; ++t) {
    v(t, 0) = 10 + t;
    v(t, 1) = 20 + t;
    e[t] = 100 + t;
  }
  EXPECT_EQ(narx.num_inputs(), 8);
  EXPECT_EQ(narx.num_parameters(), 5u * 8 + 5 + 5 + 1);
  EXPECT_EQ(narx.open_loop_regressors(v, e).col(0),
            (Eigen::VectorXd(8) << 12, 11, 10, 22, 21, 20, 101, 100).finished());
  EXPECT_NE(testing::error_message<Error>([&] {
              narx.open_loop_regressors(v.leftCols(1), e);
            }).find("1 input channel(s), the network has 2"),
            std::string::npos);
}

// The closed loop and its RTRL Jacobian with two channels, as for one:
// the static network fed its own outputs, and central differences.
TEST(Narx, SeveralChannelsClosedLoopAndDynamicJacobian) {
  NarxOptions o = small(1);
  o.inputs = 2;
  const Narx narx(o);
  Rng rng(8);
  Eigen::VectorXd w(narx.num_parameters());
  narx.initialise(w, rng);
  w *= 2.0;
  Eigen::MatrixXd v(90, 2);
  v.col(0) = smooth_input(90, 0.3);
  v.col(1) = smooth_input(90, 2.1).array().sign().matrix();  // a direction-like channel
  Eigen::VectorXd e0 = Eigen::VectorXd::Zero(90);
  e0.head(3) << 0.2, -0.1, 0.05;
  Eigen::MatrixXd jac;
  const Eigen::VectorXd sim = narx.simulate_closed_loop(w, v, e0, &jac);
  Eigen::VectorXd series = e0;
  series.tail(sim.size()) = sim;
  const Eigen::MatrixXd predicted = narx.mlp().predict(w, narx.open_loop_regressors(v, series));
  for (Eigen::Index s = 0; s < sim.size(); ++s) ASSERT_NEAR(predicted(0, s), sim[s], 1e-13);
  const double h = 1e-6;
  for (Eigen::Index p = 0; p < w.size(); ++p) {
    Eigen::VectorXd plus = w, minus = w;
    plus[p] += h;
    minus[p] -= h;
    const Eigen::VectorXd fd =
        (narx.simulate_closed_loop(plus, v, e0) - narx.simulate_closed_loop(minus, v, e0)) /
        (2 * h);
    EXPECT_LT((jac.col(p) - fd).cwiseAbs().maxCoeff() / (1.0 + fd.cwiseAbs().maxCoeff()), 1e-7)
        << "parameter " << p;
  }
}

TEST(Narx, RejectsBadOptionsAndSeries) {
  const auto message = [](auto change) {
    NarxOptions o;
    change(o);
    return testing::error_message<OptionError>([&] { Narx n(o); });
  };
  EXPECT_EQ(message([](NarxOptions&) {}), "no error");
  EXPECT_EQ(message([](NarxOptions& o) { o.input_delays = 0; }), "input_delays = 0: must be >= 1");
  EXPECT_NE(message([](NarxOptions& o) { o.feedback_delays = 0; }).find("feedback_delays = 0"),
            std::string::npos);
  EXPECT_NE(message([](NarxOptions& o) { o.hidden = 0; }).find("hidden = 0"), std::string::npos);
  EXPECT_NE(message([](NarxOptions& o) { o.inputs = 0; }).find("inputs = 0"), std::string::npos);
  EXPECT_NE(message([](NarxOptions& o) { o.first_input_delay = 2; }).find("first_input_delay = 2"),
            std::string::npos);
  const Narx narx(small(0));
  Eigen::VectorXd v = smooth_input(10, 0), e = Eigen::VectorXd::Zero(9);
  EXPECT_NE(testing::error_message<Error>([&] {
              narx.open_loop_regressors(v, e);
            }).find("input has 10 samples, error 9"),
            std::string::npos);
  e = Eigen::VectorXd::Zero(10);
  e[4] = NAN;
  EXPECT_NE(testing::error_message<Error>([&] { narx.open_loop_regressors(v, e); }).find("NaN"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab
