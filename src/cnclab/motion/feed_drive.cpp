#include "cnclab/motion/feed_drive.hpp"

#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/machine_fields.hpp"

namespace cnclab {
namespace {

void require(bool ok, const char* field, double value, const char* rule) {
  if (!ok || !std::isfinite(value)) {
    std::ostringstream v;
    v << value;
    throw OptionError(field, v.str(), std::isfinite(value) ? rule : "must be finite");
  }
}

// coarse / fine as an integer; the periods must nest exactly. The error
// names the finer period's field.
int ratio(double coarse, double fine, const char* fine_field, const char* coarse_field) {
  const double r = coarse / fine;
  const double n = std::round(r);
  const std::string rule =
      std::string("must divide ") + coarse_field + " into a whole number (>= 1) of steps";
  require(n >= 1 && std::abs(r - n) <= 1e-9 * n, fine_field, fine, rule.c_str());
  return static_cast<int>(n);
}

double quantise(double value, double quantum) {
  return quantum > 0 ? std::round(value / quantum) * quantum : value;
}

// State of one drive between controller ticks.
class Drive {
 public:
  Drive(const FeedDriveOptions& o, const DriveTiming& t, double start)
      : o_(o),
        inertia_(o.total_inertia()),
        rad_per_mm_(2 * std::numbers::pi / o.screw_lead),
        theta_(start * rad_per_mm_),
        table_(start),
        encoder_quantum_(o.motor_encoder_counts > 0
                             ? 2 * std::numbers::pi / static_cast<double>(o.motor_encoder_counts)
                             : 0.0),
        theta_measured_(quantise(theta_, encoder_quantum_)),
        t_velocity_(t.velocity_loop_period),
        dt_(t.integration_step),
        velocity_ticks_(t.velocity_ticks_per_control()),
        substeps_(t.substeps_per_velocity_tick()) {}

  double nut() const { return theta_ / rad_per_mm_; }
  double tool() const {
    return table_ + o_.lead_error_amplitude * std::sin(rad_per_mm_ * nut() + o_.lead_error_phase);
  }

  // One controller period with velocity command v_cmd [mm/s].
  void control_period(double v_cmd) {
    const double w_cmd = rad_per_mm_ * v_cmd;
    for (int m = 0; m < velocity_ticks_; ++m) {
      const double theta_m = quantise(theta_, encoder_quantum_);
      const double w_meas = (theta_m - theta_measured_) / t_velocity_;
      theta_measured_ = theta_m;
      const double e = w_cmd - w_meas;
      double tau =
          o_.velocity_gain * (e + (integral_ + e * t_velocity_) / o_.velocity_integral_time);
      if (std::abs(tau) > o_.torque_limit) {
        tau = std::copysign(o_.torque_limit, tau);  // saturated: integrator held
      } else {
        integral_ += e * t_velocity_;
      }
      for (int s = 0; s < substeps_; ++s) mechanics_step(tau);
    }
  }

 private:
  void mechanics_step(double tau) {
    const double drive = tau - o_.viscous_friction * w_;
    double w_new;
    if (w_ == 0.0) {
      // Sticking until the drive torque exceeds breakaway; then slipping
      // against the friction at zero speed (tau_s).
      if (std::abs(drive) <= o_.static_friction) {
        w_new = 0.0;
      } else {
        w_new = dt_ / inertia_ * (drive - std::copysign(o_.static_friction, drive));
      }
    } else {
      const double x = w_ / o_.stribeck_velocity;
      const double friction = std::copysign(
          o_.coulomb_friction + (o_.static_friction - o_.coulomb_friction) * std::exp(-x * x), w_);
      w_new = w_ + dt_ / inertia_ * (drive - friction);
      // A sign change within the step means the axis stopped: stick (only
      // with friction; without it the linear dynamics run through zero).
      if (o_.static_friction > 0 && w_new * w_ < 0) w_new = 0.0;
    }
    theta_ += 0.5 * dt_ * (w_ + w_new);
    w_ = w_new;
    // Backlash: the table moves only when the nut pushes it at one flank.
    const double half_gap = 0.5 * o_.backlash;
    const double d = nut() - table_;
    if (d > half_gap) table_ = nut() - half_gap;
    if (d < -half_gap) table_ = nut() + half_gap;
  }

  const FeedDriveOptions& o_;
  double inertia_, rad_per_mm_;
  double theta_, w_ = 0.0, table_;
  double encoder_quantum_, theta_measured_;
  double integral_ = 0.0;
  double t_velocity_, dt_;
  int velocity_ticks_, substeps_;
};

}  // namespace

void DriveTiming::validate() const {
  drive_timing_fields().check(*this);  // each period > 0 (machine_fields.cpp)
  velocity_ticks_per_control();
  substeps_per_velocity_tick();
}

int DriveTiming::velocity_ticks_per_control() const {
  return ratio(controller_period, velocity_loop_period, "velocity_loop_period",
               "controller_period");
}

int DriveTiming::substeps_per_velocity_tick() const {
  return ratio(velocity_loop_period, integration_step, "integration_step", "velocity_loop_period");
}

double FeedDriveOptions::total_inertia() const {
  const double lead_m = screw_lead * 1e-3;
  return motor_inertia + screw_inertia + table_mass * std::pow(lead_m / (2 * std::numbers::pi), 2);
}

void FeedDriveOptions::validate() const {
  feed_drive_fields().check(*this);  // per-key rules (machine_fields.cpp)
  require(total_inertia() > 0, "motor_inertia", motor_inertia,
          "total inertia J_motor + J_screw + m (p/2pi)^2 must be > 0");
  require(static_friction >= coulomb_friction, "static_friction", static_friction,
          "must be >= coulomb_friction");
}

AxisResponse simulate_axis(const FeedDriveOptions& axis, const DriveTiming& timing,
                           const std::vector<double>& reference_position,
                           const std::vector<double>& reference_velocity, Rng& noise) {
  axis.validate();
  timing.validate();
  if (reference_position.size() != reference_velocity.size() || reference_position.empty()) {
    std::ostringstream m;
    m << "simulate_axis: reference positions (" << reference_position.size() << ") and velocities ("
      << reference_velocity.size() << ") must be non-empty and equal in length";
    throw Error(m.str());
  }
  const std::size_t n = reference_position.size();
  AxisResponse out;
  out.actual.resize(n);
  out.measured.resize(n);
  out.following_error.resize(n);
  Drive drive(axis, timing, reference_position[0]);
  for (std::size_t k = 0; k < n; ++k) {
    const double x = drive.tool();
    const double noisy = axis.scale_noise > 0 ? x + axis.scale_noise * noise.normal() : x;
    const double x_meas = quantise(noisy, axis.scale_resolution);
    out.actual[k] = x;
    out.measured[k] = x_meas;
    out.following_error[k] = reference_position[k] - x_meas;
    drive.control_period(axis.position_gain * (reference_position[k] - x_meas) +
                         axis.velocity_feedforward * reference_velocity[k]);
  }
  return out;
}

}  // namespace cnclab
