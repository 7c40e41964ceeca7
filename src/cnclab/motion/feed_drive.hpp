#pragma once
// Simulated ball-screw feed drive of one axis (we have no machine: seed 002
// logged a real biaxial router; docs/motion.md shows the block diagram).
//
// Control (cascade, as in industrial servo drives):
//   position loop, P, every controller_period (the CNC's 1 ms):
//     v_cmd = Kp (r - x_meas) + k_ff v_ref                         [mm/s]
//   velocity loop, PI, every velocity_loop_period, on the motor encoder:
//     e_w = (2 pi / p) v_cmd - w_meas,  I += e_w T_v,
//     tau = Kv (e_w + I / Ti), |tau| <= tau_max (integration stops while saturated)
//   the current loop is ideal (torque = command, held between updates).
// Mechanics, integrated with step integration_step (explicit Euler on w,
// trapezoid on theta):
//   J w' = tau - b w - tau_f(w),   J = J_motor + J_screw + m (p / 2 pi)^2
//   tau_f = sgn(w) (tau_c + (tau_s - tau_c) exp(-(w / w_s)^2))    (Stribeck)
//   with sticking at w = 0 while |tau - b w| <= tau_s (Karnopp).
//   nut position x_n = theta p / 2 pi; table x_t follows x_n through a
//   backlash gap g (play operator: |x_n - x_t| <= g/2);
//   tool position x = x_t + A_lead sin(2 pi x_n / p + phi)  (ball-screw lead
//   error / runout, one period per screw turn);
//   linear scale x_meas = round((x + noise) / resolution) * resolution.
#include <cstdint>
#include <vector>

#include "cnclab/core/rng.hpp"

namespace cnclab {

// Loop rates and the integration step; each period must be an integer
// multiple of the next finer one.
struct DriveTiming {
  double controller_period = 1e-3;       // position loop = interpolator period [s] (seed 002: 1 ms)
  double velocity_loop_period = 125e-6;  // drive velocity loop [s] (8 kHz, a common drive rate)
  double integration_step = 25e-6;       // mechanics integration step [s]

  void validate() const;
  int velocity_ticks_per_control() const;  // controller_period / velocity_loop_period
  int substeps_per_velocity_tick() const;  // velocity_loop_period / integration_step
};

struct FeedDriveOptions {
  // Mechanics.
  double motor_inertia = 1.2e-4;  // J_motor [kg m^2] (400 W AC servo class)
  double screw_inertia = 6.0e-5;  // J_screw [kg m^2] (steel, 16 mm x 1 m: pi rho L d^4 / 32)
  double table_mass = 25.0;       // m, moving mass [kg]; reflected as m (p / 2 pi)^2
  double screw_lead = 10.0;       // p, table travel per screw turn [mm]
  double torque_limit = 3.8;      // tau_max [N m] (about 3x rated torque)
  // Friction (motor side).
  double viscous_friction = 1.0e-3;  // b [N m s/rad]
  double coulomb_friction = 0.15;    // tau_c [N m]; 0 = off
  double static_friction = 0.20;     // tau_s [N m] (breakaway, >= tau_c); 0 = off
  double stribeck_velocity = 0.5;    // w_s [rad/s] (0.8 mm/s at 10 mm lead)
  // Transmission errors.
  double backlash = 0.005;              // g, total gap [mm]; 0 = off
  double lead_error_amplitude = 0.003;  // A_lead [mm]; 0 = off
  double lead_error_phase = 0.0;        // phi [rad]
  // Control.
  double position_gain = 40.0;         // Kp [1/s] (the "Kv factor" of CNC tuning)
  double velocity_feedforward = 0.95;  // k_ff [-], in [0, 1]
  double velocity_gain = 0.146;        // Kv [N m s/rad]: Kv / J = 600 rad/s with the defaults above
  double velocity_integral_time = 8e-3;  // Ti [s]
  // Measurement.
  double scale_resolution = 1e-4;  // linear scale quantum [mm] (0.1 um); 0 = ideal
  double scale_noise = 2e-4;       // linear scale noise standard deviation [mm]; 0 = off
  std::uint64_t motor_encoder_counts = 131072;  // counts per motor turn (17 bit); 0 = ideal

  void validate() const;
  // J_motor + J_screw + m (p / 2 pi)^2 [kg m^2] (p converted to m).
  double total_inertia() const;
};

// One axis' response, one value per controller period.
struct AxisResponse {
  std::vector<double> actual;    // tool position x at t_k [mm]
  std::vector<double> measured;  // linear scale reading at t_k [mm]
  // Following error as the controller logs it: r_k - x_meas(t_k) [mm].
  std::vector<double> following_error;
};

// Runs the axis from rest at reference[0] through the references sampled
// every timing.controller_period (position [mm] and velocity feed-forward
// [mm/s], same length). `noise` draws the scale noise.
AxisResponse simulate_axis(const FeedDriveOptions& axis, const DriveTiming& timing,
                           const std::vector<double>& reference_position,
                           const std::vector<double>& reference_velocity, Rng& noise);

}  // namespace cnclab
