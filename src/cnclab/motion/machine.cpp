#include "cnclab/motion/machine.hpp"

#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/motion/machine_fields.hpp"

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

}  // namespace

void MachineOptions::validate() const {
  prefixed("timing.", [&] { timing.validate(); });
  for (int i = 0; i < 2; ++i) {
    prefixed(std::string("axes.") + kAxisNames[i] + ".", [&] { axes[i].validate(); });
  }
}

MachineOptions read_machine(const ConfigReader& section) {
  MachineOptions m;
  machine_fields().read(section, m);
  section.validate([&] { m.validate(); });
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
