#include "cnclab/motion/machine.hpp"

#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr const char* kAxisNames[2] = {"x", "y"};

template <class F>
void prefixed(const std::string& prefix, F&& validate) {
  try {
    validate();
  } catch (const OptionError& e) {
    throw OptionError(prefix + e.field(), e.value(), e.rule());
  }
}

DriveTiming read_timing(const ConfigReader& r) {
  DriveTiming t;
  t.controller_period = r.get<double>("controller_period", t.controller_period);
  t.velocity_loop_period = r.get<double>("velocity_loop_period", t.velocity_loop_period);
  t.integration_step = r.get<double>("integration_step", t.integration_step);
  r.validate([&] { t.validate(); });
  return t;
}

FeedDriveOptions read_axis(const ConfigReader& r) {
  FeedDriveOptions a;
  auto get = [&](const char* key, double& field) { field = r.get<double>(key, field); };
  get("motor_inertia", a.motor_inertia);
  get("screw_inertia", a.screw_inertia);
  get("table_mass", a.table_mass);
  get("screw_lead", a.screw_lead);
  get("torque_limit", a.torque_limit);
  get("viscous_friction", a.viscous_friction);
  get("coulomb_friction", a.coulomb_friction);
  get("static_friction", a.static_friction);
  get("stribeck_velocity", a.stribeck_velocity);
  get("backlash", a.backlash);
  get("lead_error_amplitude", a.lead_error_amplitude);
  get("lead_error_phase", a.lead_error_phase);
  get("position_gain", a.position_gain);
  get("velocity_feedforward", a.velocity_feedforward);
  get("velocity_gain", a.velocity_gain);
  get("velocity_integral_time", a.velocity_integral_time);
  get("scale_resolution", a.scale_resolution);
  get("scale_noise", a.scale_noise);
  a.motor_encoder_counts = r.get<std::uint64_t>("motor_encoder_counts", a.motor_encoder_counts);
  r.validate([&] { a.validate(); });
  return a;
}

}  // namespace

void MachineOptions::validate() const {
  prefixed("timing.", [&] { timing.validate(); });
  for (int i = 0; i < 2; ++i) {
    prefixed(std::string("axes.") + kAxisNames[i] + ".", [&] { axes[i].validate(); });
  }
}

MachineOptions read_machine(const ConfigReader& section) {
  MachineOptions m;
  m.name = section.get<std::string>("name", m.name);
  m.timing = read_timing(section.section("timing"));
  const ConfigReader axes = section.section("axes");
  for (int i = 0; i < 2; ++i) m.axes[i] = read_axis(axes.section(kAxisNames[i]));
  return m;
}

MachineOptions load_machine(const std::filesystem::path& file) {
  const ConfigDocument doc = ConfigDocument::load(file);
  const ConfigReader root = doc.root();
  if (!root.has("machine")) root.fail("machine", "is required (the machine section)");
  MachineOptions m = read_machine(root.section("machine"));
  doc.check_all_consumed();
  return m;
}

MachineResponse simulate_machine(const MachineOptions& machine,
                                 const ReferenceTrajectory& reference, std::uint64_t seed) {
  machine.validate();
  if (std::abs(reference.period - machine.timing.controller_period) >
      1e-12 * machine.timing.controller_period) {
    std::ostringstream m;
    m << "simulate_machine: reference period " << reference.period
      << " s differs from the controller period " << machine.timing.controller_period << " s";
    throw Error(m.str());
  }
  const Eigen::Index n = reference.samples();
  MachineResponse out;
  out.actual.resize(n, 2);
  out.measured.resize(n, 2);
  out.following_error.resize(n, 2);
  for (int i = 0; i < 2; ++i) {
    std::vector<double> r(n), v(n);
    for (Eigen::Index k = 0; k < n; ++k) {
      r[k] = reference.position(k, i);
      v[k] = reference.velocity(k, i);
    }
    Rng noise(seed, std::string("feed_drive.") + kAxisNames[i]);
    const AxisResponse a = simulate_axis(machine.axes[i], machine.timing, r, v, noise);
    for (Eigen::Index k = 0; k < n; ++k) {
      out.actual(k, i) = a.actual[k];
      out.measured(k, i) = a.measured[k];
      out.following_error(k, i) = a.following_error[k];
    }
  }
  return out;
}

}  // namespace cnclab
