// The contour-error feedrate optimisation on a short path with a predictor
// fitted in the test: a linear ARX model of each simulated axis (least
// squares on a different path), embedded in a one-unit tanh NARX in its
// linear range. Checked against the simulated machine, the truth the
// predictor only approximates.
#include "cnclab/studies/contour_error/feedrate_optimisation.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <algorithm>
#include <cstdio>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/studies/contour_error/contour_verification.hpp"

namespace cnclab {
namespace {

constexpr std::size_t kDelays = 4;  // input and feedback delays of the ARX
constexpr double kLinear = 1e-3;    // tanh argument scale: tanh(h) = h (1 - h^2/3)
constexpr double kTimeTol = 1e-3;   // traversal times compared to one 1 ms tick [s]

// e(t) = sum_j b_j v(t-j) + sum_k a_k e(t-k) + c, j = 0..3, k = 1..4, fitted
// by least squares to one axis of a simulated run, then written as a NARX
// with one tanh unit: h = kLinear (normalised ARX), out = h-linear / kLinear.
NarxAxisModel fitted_linear_narx(const Eigen::VectorXd& v, const Eigen::VectorXd& e) {
  const double vr = 300.0, er = 0.2;  // normalisation ranges [-vr, vr] mm/s, [-er, er] mm
  const auto n = v.size(), first = static_cast<Eigen::Index>(kDelays);
  Eigen::MatrixXd X(n - first, 2 * kDelays + 1);
  Eigen::VectorXd y(n - first);
  for (Eigen::Index t = first; t < n; ++t) {
    for (Eigen::Index j = 0; j < first; ++j) X(t - first, j) = v[t - j] / vr;
    for (Eigen::Index k = 1; k <= first; ++k) X(t - first, first + k - 1) = e[t - k] / er;
    X(t - first, 2 * first) = 1.0;
    y[t - first] = e[t] / er;
  }
  const Eigen::VectorXd w = X.colPivHouseholderQr().solve(y);
  NarxOptions o;
  o.input_delays = o.feedback_delays = kDelays;
  o.hidden = 1;
  NarxAxisModel m{
      o, Eigen::VectorXd(2 * kDelays + 3),  // W1 (8), b1, W2, b2
      MinMaxNormaliser(Eigen::VectorXd::Constant(1, -vr), Eigen::VectorXd::Constant(1, vr)),
      MinMaxNormaliser(Eigen::VectorXd::Constant(1, -er), Eigen::VectorXd::Constant(1, er))};
  m.params.head(2 * kDelays) = kLinear * w.head(2 * kDelays);  // W1
  m.params[2 * kDelays] = kLinear * w[2 * kDelays];            // b1
  m.params[2 * kDelays + 1] = 1.0 / kLinear;                   // W2
  m.params[2 * kDelays + 2] = 0.0;                             // b2
  return m;
}

// The predictor: both axes fitted on a 40 mm circle at its planned feed.
ContourPredictor fitted_predictor(const VerificationOptions& v) {
  const CirclePath train(Vec2(50, 50), 12.0, 0.0, 3.4);
  const ReferenceTrajectory r = interpolate(train, plan_feedrate(train));
  const MachineResponse m = simulate_machine(v.machine, r, 7);
  return ContourPredictor(fitted_linear_narx(r.velocity.col(0), m.following_error.col(0)),
                          fitted_linear_narx(r.velocity.col(1), m.following_error.col(1)));
}

// An S-bend of ~30 mm with radii of curvature down to a few mm.
const CubicBezierPath& test_path() {
  static const CubicBezierPath path({Vec2(0, 0), Vec2(20, 0), Vec2(0, 12), Vec2(20, 12)});
  return path;
}

TEST(FeedrateOptimisation, ConstraintHoldsOnTheSimulatedMachine) {
  VerificationOptions v;
  ContourPredictor predictor = fitted_predictor(v);
  const FeedrateProfile free = plan_feedrate(test_path());
  const ReferenceTrajectory free_ref = interpolate(test_path(), free);
  const ContourCheck free_check = check_on_machine(test_path(), free_ref, v);
  // A tolerance half the unconstrained plan's simulated maximum: binding.
  FeedrateOptimisationOptions o;
  o.tolerance = 0.5 * free_check.max;
  const FeedrateOptimisationResult res = optimise_feedrate(test_path(), predictor, o);
  for (const auto& h : res.history) {
    std::printf("plan: worst predicted %.2f um, time %.4f s, %zu ticks over, min cap %.1f mm/s\n",
                h.worst_predicted * 1e3, h.time, h.ticks_over, h.min_cap);
  }
  ASSERT_EQ(res.status, OptimisationStatus::converged) << res.reason;
  ASSERT_GE(res.history.size(), 2u);
  EXPECT_GT(res.history.front().worst_predicted, o.tolerance);
  EXPECT_LE(res.history.back().worst_predicted, o.tolerance);
  EXPECT_LT(res.history.back().worst_predicted, res.history.front().worst_predicted);
  EXPECT_GE(res.profile.total_time(), res.unconstrained_time());
  EXPECT_NEAR(res.unconstrained_time(), free.total_time(), 1e-9);
  v.tolerance = o.tolerance;
  const ContourCheck check = check_on_machine(test_path(), res.reference, v);
  std::printf(
      "tolerance %.2f um: simulated max %.2f um (unconstrained %.2f), share within %.4f, "
      "time %.4f s (unconstrained %.4f)\n",
      o.tolerance * 1e3, check.max * 1e3, free_check.max * 1e3, check.share_within, check.time,
      free.total_time());
  EXPECT_GE(check.share_within, 0.999);
  EXPECT_LT(check.max, free_check.max);
}

// The loop with the simulated machine itself as the error model (the job's
// oracle), lower-only and two-sided (raise_caps): both plans keep every tick
// within the tolerance on the machine (a separate machine run checks), and
// raising caps the lower-only loop never raises is not slower.
TEST(FeedrateOptimisation, SimulatedMachineAsModelMeetsTheTolerance) {
  VerificationOptions v;
  const FeedrateProfile free = plan_feedrate(test_path());
  const ContourCheck free_check = check_on_machine(test_path(), interpolate(test_path(), free), v);
  FeedrateOptimisationOptions o;
  o.tolerance = v.tolerance = 0.5 * free_check.max;
  std::size_t calls = 0;
  const ContourErrorModel machine = [&](const ReferenceTrajectory& r) {
    ++calls;
    return check_on_machine(test_path(), r, v).simulated;
  };
  const FeedrateOptimisationResult lower = optimise_feedrate(test_path(), machine, o);
  ASSERT_EQ(lower.status, OptimisationStatus::converged) << lower.reason;
  EXPECT_EQ(calls, lower.history.size());
  o.raise_caps = true;
  o.max_iterations = 8;
  const FeedrateOptimisationResult both = optimise_feedrate(test_path(), machine, o);
  ASSERT_EQ(both.status, OptimisationStatus::converged) << both.reason;
  for (const auto* res : {&lower, &both}) {
    const ContourCheck check = check_on_machine(test_path(), res->reference, v);
    std::printf("%s: %.4f s (unconstrained %.4f), simulated max %.2f um of %.2f, %zu plans\n",
                res == &lower ? "lower-only" : "raise_caps", check.time, free.total_time(),
                check.max * 1e3, o.tolerance * 1e3, res->history.size());
    EXPECT_LE(check.max, o.tolerance);
    EXPECT_GT(check.time, free.total_time());
  }
  EXPECT_LE(both.profile.total_time(), lower.profile.total_time() + kTimeTol);
}

// The S-bend with the simulated machine as the loop's model and a tolerance
// of 0.6 times the unconstrained plan's largest simulated contour error.
struct OnTheMachine {
  VerificationOptions v;
  FeedrateOptimisationOptions o;
  ContourErrorModel machine = [this](const ReferenceTrajectory& r) {
    return check_on_machine(test_path(), r, v).simulated;
  };
  OnTheMachine() {
    const FeedrateProfile free = plan_feedrate(test_path());
    o.tolerance = 0.6 * check_on_machine(test_path(), interpolate(test_path(), free), v).max;
  }
  OnTheMachine(const OnTheMachine&) = delete;  // `machine` refers to this one's `v`
};

// Margins per feed band: the converged plan keeps every tick's modelled
// error within eps_max - m(|v|) of its own band (checked tick by tick here),
// and a band whose margin reaches eps_max at the speeds every plan passes
// through (standstill at the ends) leaves nothing to plan: infeasible.
TEST(FeedrateOptimisation, MarginsPerFeedBandHoldTickByTick) {
  OnTheMachine m;
  FeedrateOptimisationOptions& o = m.o;
  const ContourErrorModel& machine = m.machine;
  o.margin_bands = {{30.0}, {0.05 * o.tolerance, 0.25 * o.tolerance}};
  const FeedrateOptimisationResult res = optimise_feedrate(test_path(), machine, o);
  ASSERT_EQ(res.status, OptimisationStatus::converged) << res.reason;
  std::size_t slow = 0, fast = 0;
  for (Eigen::Index k = 0; k < res.reference.samples(); ++k) {
    const double speed = res.reference.velocity.row(k).norm();
    const double m = speed < 30.0 ? 0.05 * o.tolerance : 0.25 * o.tolerance;
    (speed < 30.0 ? slow : fast) += 1;
    ASSERT_LE(res.predicted[static_cast<std::size_t>(k)], o.tolerance - m + 1e-15) << k;
  }
  EXPECT_GT(slow, 0u);
  EXPECT_GT(fast, 0u);
  EXPECT_LE(res.history.back().worst_excess, 0.0);
  EXPECT_GT(res.history.front().worst_excess, 0.0);

  o.margin_bands.margin[0] = o.tolerance;  // nothing left below 30 mm/s
  const FeedrateOptimisationResult none = optimise_feedrate(test_path(), machine, o);
  EXPECT_EQ(none.status, OptimisationStatus::infeasible) << none.reason;
  o.margin_bands.margin = {0.1};  // one value for two bands
  try {
    optimise_feedrate(test_path(), machine, o);
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "margin_bands.margin");
  }
}

// Margins after a change of direction, on a hand-made reference: +x from
// rest at tick 2, -x from tick 6, a window of 2 ms (ticks 2-4 and 6-8).
TEST(FeedrateOptimisation, MarginsAfterAChangeOfDirectionHoldForTheWindow) {
  ReferenceTrajectory r;
  const std::vector<double> vx = {0, 0, 60, 60, 60, 60, -20, -20, -20, -20, -20};
  r.velocity = Eigen::MatrixX2d::Zero(static_cast<Eigen::Index>(vx.size()), 2);
  r.position = r.velocity;
  for (std::size_t k = 0; k < vx.size(); ++k) r.velocity(static_cast<Eigen::Index>(k), 0) = vx[k];
  FeedrateOptimisationOptions o;
  o.margin_bands = {{50.0}, {0.001, 0.002}, 0.002, {0.005, 0.006}};
  EXPECT_EQ(o.tick_margins(r), (std::vector<double>{0.001, 0.001, 0.006, 0.006, 0.006, 0.002, 0.005,
                                                    0.005, 0.005, 0.001, 0.001}));
  o.margin_bands.reversal_window = 0;  // one class: after_reversal must be empty
  try {
    o.validate();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "margin_bands.after_reversal");
  }
  o.margin_bands.after_reversal.clear();
  EXPECT_EQ(o.tick_margins(r), (std::vector<double>{0.001, 0.001, 0.002, 0.002, 0.002, 0.002, 0.001,
                                                    0.001, 0.001, 0.001, 0.001}));
}

// The loop keeps every tick of its plan within eps_max - m_k, m_k of the
// tick's class: the first 100 ms after each axis starts (the S-bend has no
// reversal; the ticks since a start are counted here by hand), where the
// margin leaves 0.3 eps_max.
TEST(FeedrateOptimisation, MarginsAfterAStartHoldTickByTick) {
  OnTheMachine m;
  FeedrateOptimisationOptions& o = m.o;
  o.margin_bands = {
      {30.0}, {0.05 * o.tolerance, 0.1 * o.tolerance}, 0.1, {0.7 * o.tolerance, 0.7 * o.tolerance}};
  const FeedrateOptimisationResult res = optimise_feedrate(test_path(), m.machine, o);
  ASSERT_EQ(res.status, OptimisationStatus::converged) << res.reason;
  Eigen::Index started[2] = {-1, -1};
  std::size_t after = 0;
  for (Eigen::Index k = 0; k < res.reference.samples(); ++k) {
    for (int a = 0; a < 2; ++a) {
      if (started[a] < 0 && std::abs(res.reference.velocity(k, a)) > 1e-3) started[a] = k;
    }
    const bool recent =
        (started[0] >= 0 && k - started[0] <= 100) || (started[1] >= 0 && k - started[1] <= 100);
    const double speed = res.reference.velocity.row(k).norm();
    const double m = recent ? 0.7 * o.tolerance : (speed < 30.0 ? 0.05 : 0.1) * o.tolerance;
    after += recent ? 1 : 0;
    ASSERT_LE(res.predicted[static_cast<std::size_t>(k)], o.tolerance - m + 1e-15) << k;
  }
  EXPECT_GE(after, 101u);
}

// A model that predicts twice the tolerance at every tick slower than
// 1 mm/s (a start-up transient: the plan's first and last jerk-limited ticks,
// the same under any cap) and the machine's error elsewhere: no plan meets
// the bound at every tick; with standstill_speed 1 mm/s those ticks are not
// held to it and every other tick is.
TEST(FeedrateOptimisation, TicksAtStandstillAreNotHeldToTheBoundWhenAsked) {
  OnTheMachine m;
  FeedrateOptimisationOptions& o = m.o;
  const ContourErrorModel transient = [&](const ReferenceTrajectory& r) {
    std::vector<double> e = m.machine(r);
    for (Eigen::Index k = 0; k < r.samples(); ++k) {
      if (r.velocity.row(k).norm() < 1.0) e[static_cast<std::size_t>(k)] = 2 * o.tolerance;
    }
    return e;
  };
  const FeedrateOptimisationResult judged = optimise_feedrate(test_path(), transient, o);
  EXPECT_EQ(judged.status, OptimisationStatus::infeasible) << judged.reason;
  o.standstill_speed = 1.0;
  const FeedrateOptimisationResult res = optimise_feedrate(test_path(), transient, o);
  ASSERT_EQ(res.status, OptimisationStatus::converged) << res.reason;
  std::size_t standstill = 0;
  for (Eigen::Index k = 0; k < res.reference.samples(); ++k) {
    const double eps = res.predicted[static_cast<std::size_t>(k)];
    if (res.reference.velocity.row(k).norm() < 1.0) {
      ++standstill;
      EXPECT_EQ(eps, 2 * o.tolerance) << k;
    } else {
      ASSERT_LE(eps, o.tolerance) << k;
    }
  }
  EXPECT_GT(standstill, 0u);
  o.standstill_speed = 2.0;  // above min_speed
  try {
    o.validate();
    FAIL() << "no error";
  } catch (const OptionError& e) {
    EXPECT_EQ(e.field(), "standstill_speed");
  }
}

TEST(FeedrateOptimisation, ModelOfTheWrongLengthIsAnError) {
  const ContourErrorModel short_model = [](const ReferenceTrajectory&) {
    return std::vector<double>(3, 0.0);
  };
  EXPECT_THROW(optimise_feedrate(test_path(), short_model, FeedrateOptimisationOptions{}), Error);
}

TEST(FeedrateOptimisation, UnreachableToleranceStopsWithAReason) {
  VerificationOptions v;
  ContourPredictor predictor = fitted_predictor(v);
  FeedrateOptimisationOptions o;
  o.tolerance = 1e-7;  // 0.1 nm: below what any slowdown reaches (the model's offset)
  o.max_iterations = 6;
  const FeedrateOptimisationResult res = optimise_feedrate(test_path(), predictor, o);
  EXPECT_NE(res.status, OptimisationStatus::converged);
  EXPECT_FALSE(res.reason.empty());
  EXPECT_LE(res.history.size(), 6u);
}

TEST(FeedrateOptimisation, OptionsAreValidated) {
  FeedrateOptimisationOptions o;
  o.safety_factor = 1.5;
  EXPECT_THROW(o.validate(), OptionError);
  o = {};
  o.tolerance = -1;
  EXPECT_THROW(o.validate(), OptionError);
  o = {};
  o.max_iterations = 0;
  EXPECT_THROW(o.validate(), OptionError);
}

}  // namespace
}  // namespace cnclab
