// The real-time predictor against the batch closed-loop simulation
// (Narx::simulate_closed_loop on the normalised series, MinMaxNormaliser's
// matrix transforms): the delay bookkeeping, the history order, the
// normalisation and reset() are the predictor's own code.
#include "cnclab/nn/narx_predictor.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/stable_narx.hpp"

namespace cnclab {
namespace {

using testing::stable_narx_model;
using testing::test_velocity;

// Long enough that a wrong delay or a drifting state would show (seed 002
// predicts > 80,000 steps in closed loop).
constexpr Eigen::Index kSteps = 30000;

Eigen::VectorXd velocity_series(Eigen::Index n, double phase) {
  Eigen::VectorXd v(n);
  for (Eigen::Index t = 0; t < n; ++t) v[t] = test_velocity(t, phase);
  return v;
}

// Batch: e_hat(t), t = first_step()..T-1, in mm.
Eigen::VectorXd batch_prediction(const NarxAxisModel& m, const Eigen::VectorXd& v,
                                 const Eigen::VectorXd& e_initial) {
  const Narx narx(m.options);
  const Eigen::VectorXd vn = m.input.transform(v.transpose()).transpose();
  const Eigen::VectorXd en = m.output.transform(e_initial.transpose()).transpose();
  const Eigen::VectorXd sim = narx.simulate_closed_loop(m.params, vn, en);
  return m.output.inverse_transform(sim.transpose()).transpose();
}

NarxOptions options(std::size_t d0, std::size_t dv, std::size_t de, std::size_t hidden,
                    Activation f) {
  NarxOptions o;
  o.first_input_delay = d0;
  o.input_delays = dv;
  o.feedback_delays = de;
  o.hidden = hidden;
  o.hidden_activation = f;
  return o;
}

// Both delay conventions, more input than feedback delays and the reverse,
// tanh and sigmoid units, the paper's 12 neurons with 4/4 delays.
std::vector<NarxOptions> architectures() {
  return {options(0, 4, 4, 12, Activation::tanh), options(1, 4, 4, 12, Activation::tanh),
          options(0, 2, 5, 6, Activation::sigmoid), options(1, 5, 2, 3, Activation::tanh),
          options(0, 1, 1, 4, Activation::tanh)};
}

TEST(NarxPredictor, EqualsTheBatchClosedLoopFromMeasuredInitialStates) {
  std::uint64_t seed = 3;
  for (const NarxOptions& o : architectures()) {
    const NarxAxisModel m = stable_narx_model(o, ++seed);
    const Narx narx(o);
    const Eigen::Index t0 = narx.first_step();
    const Eigen::VectorXd v = velocity_series(kSteps, 0.3);
    Eigen::VectorXd e_initial = Eigen::VectorXd::Zero(kSteps);
    for (Eigen::Index t = 0; t < t0; ++t) e_initial[t] = 0.01 * static_cast<double>(t + 1) - 0.03;
    const Eigen::VectorXd batch = batch_prediction(m, v, e_initial);

    NarxPredictor p(m);
    ASSERT_EQ(p.error_history(), o.feedback_delays);
    ASSERT_EQ(p.velocity_history(), o.first_input_delay + o.input_delays - 1);
    const auto nv = static_cast<Eigen::Index>(p.velocity_history());
    const auto ne = static_cast<Eigen::Index>(p.error_history());
    ASSERT_EQ(p.reset({v.data() + t0 - nv, static_cast<std::size_t>(nv)},
                      {e_initial.data() + t0 - ne, static_cast<std::size_t>(ne)}),
              PredictorStatus::ok);
    double max_diff = 0;
    for (Eigen::Index t = t0; t < kSteps; ++t) {
      double e = std::nan("");
      ASSERT_EQ(p.step(v[t], e), PredictorStatus::ok);
      max_diff = std::max(max_diff, std::abs(e - batch[t - t0]));
    }
    // Both step through Narx::step on the same regressors: bit for bit.
    EXPECT_EQ(max_diff, 0.0) << "D_V " << o.input_delays << " D_E " << o.feedback_delays << " d0 "
                             << o.first_input_delay;
    EXPECT_GT(batch.cwiseAbs().maxCoeff(), 1e-3);  // a non-trivial output
  }
}

// reset(): the state of a trajectory starting from standstill, i.e. the
// batch simulation of the series preceded by first_step() samples of v = 0
// with initial errors 0; and a second run after reset() repeats the first.
TEST(NarxPredictor, ResetIsRestAndRepeatsARun) {
  std::uint64_t seed = 20;
  for (const NarxOptions& o : architectures()) {
    const NarxAxisModel m = stable_narx_model(o, ++seed);
    const Eigen::Index t0 = Narx(o).first_step();
    const Eigen::Index n = 2000;
    Eigen::VectorXd v = Eigen::VectorXd::Zero(t0 + n);
    for (Eigen::Index t = 0; t < n; ++t) v[t0 + t] = test_velocity(t, 1.1);
    const Eigen::VectorXd batch = batch_prediction(m, v, Eigen::VectorXd::Zero(t0 + n));

    NarxPredictor p(m);
    std::vector<double> first(static_cast<std::size_t>(n));
    for (Eigen::Index t = 0; t < n; ++t) {
      ASSERT_EQ(p.step(v[t0 + t], first[static_cast<std::size_t>(t)]), PredictorStatus::ok);
      ASSERT_EQ(first[static_cast<std::size_t>(t)], batch[t]) << "t " << t;
    }
    p.reset();
    for (Eigen::Index t = 0; t < n; ++t) {
      double e = 0;
      p.step(v[t0 + t], e);
      ASSERT_EQ(e, first[static_cast<std::size_t>(t)]) << "after reset, t " << t;
    }
  }
}

// A bad tick changes nothing: the next good ticks equal those of a
// predictor that never saw it.
TEST(NarxPredictor, BadInputLeavesStateAndOutputUnchanged) {
  const NarxOptions o = options(0, 4, 4, 12, Activation::tanh);
  const NarxAxisModel m = stable_narx_model(o, 7);
  NarxPredictor p(m), reference(m);
  double e = 0, e_ref = 0;
  for (Eigen::Index t = 0; t < 50; ++t) {
    p.step(test_velocity(t, 0), e);
    reference.step(test_velocity(t, 0), e_ref);
  }
  const double before = e;
  for (double bad : {std::nan(""), std::numeric_limits<double>::infinity(),
                     -std::numeric_limits<double>::infinity()}) {
    EXPECT_EQ(p.step(bad, e), PredictorStatus::non_finite_input);
    EXPECT_EQ(e, before);
  }
  const std::vector<double> three(3, 0.0), four(4, 0.0);
  std::vector<double> nan_errors(4, 0.0);
  nan_errors[2] = std::nan("");
  EXPECT_EQ(p.reset(four, four), PredictorStatus::wrong_history_length);  // needs 3 velocities
  EXPECT_EQ(p.reset(three, three), PredictorStatus::wrong_history_length);
  EXPECT_EQ(p.reset(three, nan_errors), PredictorStatus::non_finite_input);
  for (Eigen::Index t = 50; t < 500; ++t) {
    ASSERT_EQ(p.step(test_velocity(t, 0), e), PredictorStatus::ok);
    reference.step(test_velocity(t, 0), e_ref);
    ASSERT_EQ(e, e_ref) << "t " << t;
  }
  EXPECT_STREQ(to_string(PredictorStatus::non_finite_input), "non-finite input");
}

// Two input channels (velocity and a second series in its own range):
// tick by tick equals the batch closed loop on the normalised channels, and
// a tick with the wrong channel count changes nothing.
TEST(NarxPredictor, SeveralChannelsEqualTheBatchClosedLoop) {
  NarxOptions o = options(0, 4, 4, 8, Activation::tanh);
  o.inputs = 2;
  const Narx narx(o);
  Rng rng(3);
  NarxAxisModel m{
      o, Eigen::VectorXd(narx.num_parameters()),
      MinMaxNormaliser(Eigen::Vector2d(-300, -1), Eigen::Vector2d(300, 1)),
      MinMaxNormaliser(Eigen::VectorXd::Constant(1, -0.4), Eigen::VectorXd::Constant(1, 0.4))};
  narx.initialise(m.params, rng);
  m.params *= 0.3;  // a contracting closed loop
  const Eigen::Index n = 3000;
  Eigen::MatrixXd v(n, 2);
  for (Eigen::Index t = 0; t < n; ++t) {
    v(t, 0) = test_velocity(t, 0.5);
    v(t, 1) = v(t, 0) > 0 ? 1.0 : -1.0;
  }
  const Eigen::MatrixXd vn = m.input.transform(v.transpose()).transpose();
  const Eigen::VectorXd rest =
      Eigen::VectorXd::Constant(n, m.output.transform(0, 0.0));  // e = 0 initial states
  Eigen::MatrixXd vn_rest = vn;
  for (Eigen::Index c = 0; c < 2; ++c) {
    vn_rest.col(c).head(narx.first_step()).setConstant(m.input.transform(c, 0.0));
  }
  // The predictor from rest sees 0 before t = 0: the batch series with
  // first_step() rest ticks in front.
  Eigen::MatrixXd padded(n + narx.first_step(), 2);
  padded.topRows(narx.first_step()) = vn_rest.topRows(narx.first_step());
  padded.bottomRows(n) = vn;
  Eigen::VectorXd e_init = Eigen::VectorXd::Constant(n + narx.first_step(), rest[0]);
  const Eigen::VectorXd sim = narx.simulate_closed_loop(m.params, padded, e_init);
  NarxPredictor p(m);
  double e = 0;
  for (Eigen::Index t = 0; t < n; ++t) {
    const double in[2] = {v(t, 0), v(t, 1)};
    ASSERT_EQ(p.step(std::span<const double>(in, 2), e), PredictorStatus::ok);
    ASSERT_NEAR(e, m.output.inverse_transform(0, sim[t]), 1e-12) << t;
  }
  const double before = e;
  EXPECT_EQ(p.step(1.0, e), PredictorStatus::wrong_input_count);
  EXPECT_EQ(e, before);
}

TEST(NarxPredictor, RejectsInconsistentModels) {
  const NarxOptions o = options(0, 4, 4, 12, Activation::tanh);
  NarxAxisModel m = stable_narx_model(o, 1);
  NarxAxisModel short_params = m;
  short_params.params.conservativeResize(m.params.size() - 1);
  EXPECT_NE(testing::error_message<Error>([&] {
              NarxPredictor p(short_params);
            }).find("120 parameters, the network has 121"),
            std::string::npos);
  NarxAxisModel nan_params = m;
  nan_params.params[5] = std::nan("");
  EXPECT_NE(testing::error_message<Error>([&] { NarxPredictor p(nan_params); }).find("NaN"),
            std::string::npos);
  NarxAxisModel two_features = m;
  two_features.input = MinMaxNormaliser(Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, 1));
  EXPECT_NE(testing::error_message<Error>([&] { NarxPredictor p(two_features); })
                .find("input (velocity, other channels) normaliser has 2 fitted features, need "
                      "exactly 1"),
            std::string::npos);
  NarxAxisModel unfitted = m;
  unfitted.output = MinMaxNormaliser();
  EXPECT_NE(testing::error_message<Error>([&] {
              NarxPredictor p(unfitted);
            }).find("output (following error) normaliser has 0"),
            std::string::npos);
  NarxAxisModel bad_options = m;
  bad_options.options.feedback_delays = 0;
  EXPECT_NE(testing::error_message<OptionError>([&] {
              NarxPredictor p(bad_options);
            }).find("feedback_delays"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab
