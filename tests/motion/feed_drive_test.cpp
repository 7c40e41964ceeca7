// The feed-drive simulator against the closed forms of its linear loop
// (friction, backlash, lead error and measurement effects off), and the
// quadrant glitches its nonlinearities cause on a circle.
#include "cnclab/motion/feed_drive.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <unsupported/Eigen/MatrixFunctions>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/machine.hpp"

namespace cnclab {
namespace {

FeedDriveOptions linear_axis() {
  FeedDriveOptions a;
  a.coulomb_friction = a.static_friction = 0.0;
  a.backlash = 0.0;
  a.lead_error_amplitude = 0.0;
  a.scale_resolution = a.scale_noise = 0.0;
  a.motor_encoder_counts = 0;
  return a;
}

// The continuous velocity loop (velocities in mm/s; 2 pi / p cancels):
//   x' = v,  v' = (Kv/J)(v_cmd - v + z/Ti) - (b/J) v,  z' = v_cmd - v,
// state (x, v, z), input v_cmd.
struct LinearLoop {
  Eigen::Matrix3d A;
  Eigen::Vector3d B;
};
LinearLoop velocity_loop(const FeedDriveOptions& a) {
  const double J = a.total_inertia(), Kv = a.velocity_gain, Ti = a.velocity_integral_time;
  LinearLoop loop;
  loop.A << 0, 1, 0,                                     //
      0, -(Kv + a.viscous_friction) / J, Kv / (J * Ti),  //
      0, -1, 0;
  loop.B << 0, Kv / J, 1;
  return loop;
}

// Loops and integration at 10 us: the sampled cascade approximates the
// continuous one.
DriveTiming continuous_timing() {
  DriveTiming timing;
  timing.controller_period = timing.velocity_loop_period = timing.integration_step = 1e-5;
  return timing;
}

TEST(FeedDrive, ConstantVelocityFollowingErrorIsTheTypeOneLoopValue) {
  // Steady ramp r = v t: the PI velocity loop removes the viscous torque's
  // velocity error, so v_cmd = v and Kp e + k_ff v = v, e = (1 - k_ff) v / Kp,
  // whatever the sampling (checked at the default 1 ms / 125 us / 25 us).
  for (const double kff : {0.0, 0.95}) {
    FeedDriveOptions a = linear_axis();
    a.velocity_feedforward = kff;
    const DriveTiming timing;
    const double v = 100.0;
    const int n = 1500;  // 1.5 s; slowest closed-loop pole ~ Kp = 40 1/s
    std::vector<double> r(n), vr(n, v);
    for (int k = 0; k < n; ++k) r[k] = v * k * timing.controller_period;
    vr[0] = 0.0;
    Rng rng(1);
    const AxisResponse out = simulate_axis(a, timing, r, vr, rng);
    const double expected = (1 - kff) * v / a.position_gain;
    std::printf("k_ff %.2f: following error %.9f mm, closed form %.9f mm\n", kff,
                out.following_error.back(), expected);
    EXPECT_NEAR(out.following_error.back(), expected, 1e-6 * std::max(expected, 1e-3));
  }
}

TEST(FeedDrive, StepResponseMatchesTheContinuousLoop) {
  // The position loop v_cmd = Kp (r - x) closed around the velocity loop,
  // A = A_v - Kp B_v [1 0 0], B = Kp B_v, has the step response
  // x(t) = [1 0 0] (e^{At} - I) A^{-1} B r (matrix exponential).
  FeedDriveOptions a = linear_axis();
  a.velocity_feedforward = 0.0;
  const DriveTiming timing = continuous_timing();
  const double Kp = a.position_gain;
  const LinearLoop loop = velocity_loop(a);
  const Eigen::Matrix3d A = loop.A - Kp * loop.B * Eigen::RowVector3d(1, 0, 0);
  const Eigen::Vector3d B = Kp * loop.B;
  const double step = 0.5;
  const int n = 30000;  // 0.3 s
  std::vector<double> r(n, step), vr(n, 0.0);
  r[0] = 0.0;
  Rng rng(1);
  const AxisResponse out = simulate_axis(a, timing, r, vr, rng);
  double worst = 0.0, overshoot = 0.0;
  for (int k = 1; k < n; k += 50) {
    // Sample k is the position at t_k; the step was applied at t_1.
    const double t = (k - 1) * timing.controller_period;
    const Eigen::Vector3d x =
        ((A * t).exp() - Eigen::Matrix3d::Identity()) * A.inverse() * B * step;
    worst = std::max(worst, std::abs(out.actual[k] - x[0]));
    overshoot = std::max(overshoot, x[0] - step);
  }
  std::printf("step %.1f mm: max |simulated - closed form| = %.2e mm (overshoot %.3f mm)\n", step,
              worst, overshoot);
  EXPECT_LT(worst, 1e-3 * step);
}

TEST(FeedDrive, LeadErrorResidualIsTheLoopSensitivity) {
  // Only the lead error on: at constant velocity v it is an output
  // disturbance d = A sin(2 pi v t / p) that the linear scale sees, so the
  // logged following error oscillates with amplitude A |S(jw)|,
  // S = 1 / (1 + Kp G), G(s) = x_n / v_cmd = [1 0 0] (sI - A_v)^-1 B_v.
  FeedDriveOptions a = linear_axis();
  a.lead_error_amplitude = 0.003;
  const DriveTiming timing = continuous_timing();
  const double Kp = a.position_gain;
  const LinearLoop loop = velocity_loop(a);
  for (const double v : {50.0, 100.0, 200.0}) {
    const double w = 2 * std::numbers::pi * v / a.screw_lead;
    const Eigen::Matrix3cd M = std::complex<double>(0, w) * Eigen::Matrix3cd::Identity() -
                               loop.A.cast<std::complex<double>>();
    const std::complex<double> G = (M.inverse() * loop.B.cast<std::complex<double>>())(0);
    const double expected = a.lead_error_amplitude / std::abs(1.0 + Kp * G);
    const int n = 150000;  // 1.5 s
    std::vector<double> r(n), vr(n, v);
    for (int k = 0; k < n; ++k) r[k] = v * k * timing.controller_period;
    Rng rng(1);
    const AxisResponse out = simulate_axis(a, timing, r, vr, rng);
    // Least-squares fit c0 + c1 sin(wt) + c2 cos(wt) over the last 1 s.
    Eigen::MatrixXd X(100000, 3);
    Eigen::VectorXd y(100000);
    for (int i = 0; i < 100000; ++i) {
      const double t = (n - 100000 + i) * timing.controller_period;
      X.row(i) << 1.0, std::sin(w * t), std::cos(w * t);
      y[i] = out.following_error[n - 100000 + i];
    }
    const Eigen::Vector3d c = X.colPivHouseholderQr().solve(y);
    const double amplitude = std::hypot(c[1], c[2]);
    std::printf("v %5.1f mm/s (%4.1f Hz): lead-error residual %.4f um, A |S(jw)| = %.4f um\n", v,
                w / (2 * std::numbers::pi), amplitude * 1e3, expected * 1e3);
    EXPECT_NEAR(amplitude, expected, 0.01 * expected) << "v " << v;
  }
}

// Radial error e_r = |P - c| - r around a circle. A quadrant glitch is a
// fast jump of e_r right after an axis reverses (friction changes sign,
// backlash is crossed) that the loops then slowly remove. Returns the largest
// 10 ms change of e_r over windows that hold a reversal or start within
// 15 degrees after one, and the
// largest elsewhere, over the middle one of three turns.
std::pair<double, double> glitch_peaks(const MachineOptions& machine,
                                       const ReferenceTrajectory& ref) {
  const MachineResponse res = simulate_machine(machine, ref, 7);
  constexpr int kWindow = 10;  // samples (ms)
  double near = 0.0, away = 0.0;
  for (Eigen::Index k = 0; k + kWindow < ref.samples(); ++k) {
    const double turn = ref.u[k] * 3;  // turns done
    if (turn < 1.0 || turn > 2.0) continue;
    const double jump = std::abs(res.actual.row(k + kWindow).norm() - res.actual.row(k).norm());
    // Reversals: x velocity at 0 and 180 degrees, y velocity at 90 and 270.
    const double after_reversal = std::fmod(turn * 360.0, 90.0);
    // A window starting up to 10 degrees (about 10 ms) before a reversal spans it.
    double& peak = after_reversal < 15.0 || after_reversal > 80.0 ? near : away;
    peak = std::max(peak, jump);
  }
  return {near, away};
}

TEST(FeedDrive, QuadrantGlitchesAppearOnlyWithTheNonlinearities) {
  // Friction and backlash on; the lead error is off here because it is
  // periodic in position (one period per screw turn), not tied to reversals.
  // Three turns of r = 10 mm at the planned feedrate (about 140 mm/s,
  // acceleration-limited); the middle turn is measured.
  const CirclePath circle(Vec2(0, 0), 10.0, 0.0, 3 * 2 * std::numbers::pi);
  const ReferenceTrajectory ref = interpolate(circle, plan_feedrate(circle), 1e-3);
  MachineOptions machine;
  for (auto& a : machine.axes) a.lead_error_amplitude = 0.0;
  auto [near_on, away_on] = glitch_peaks(machine, ref);
  for (auto& a : machine.axes) a = linear_axis();
  auto [near_off, away_off] = glitch_peaks(machine, ref);
  std::printf(
      "largest 10 ms radial error change [um]: nonlinear: after reversals %.2f, "
      "elsewhere %.2f; linear: %.2f, %.2f\n",
      near_on * 1e3, away_on * 1e3, near_off * 1e3, away_off * 1e3);
  EXPECT_GT(near_on, 3.0 * away_on);
  EXPECT_GT(near_on, 0.005);           // a glitch of several um (friction 0.15 N m, backlash 5 um)
  EXPECT_LT(near_off, 0.1 * near_on);  // the linear loop's radial error stays smooth
}

TEST(FeedDrive, RejectsBadOptions) {
  FeedDriveOptions a;
  a.static_friction = 0.1;  // < coulomb
  EXPECT_THROW(a.validate(), OptionError);
  a = {};
  a.velocity_feedforward = 1.5;
  EXPECT_THROW(a.validate(), OptionError);
  DriveTiming t;
  t.integration_step = 3e-5;  // 125 us is not a multiple
  EXPECT_THROW(t.validate(), OptionError);
  t = {};
  t.controller_period = std::nan("");
  EXPECT_THROW(t.validate(), OptionError);
}

}  // namespace
}  // namespace cnclab
