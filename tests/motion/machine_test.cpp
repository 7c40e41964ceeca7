#include "cnclab/motion/machine.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "cnclab/core/error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

std::string config_error(const std::string& yaml) {
  testing::TempDir dir;
  const auto file = dir / "machine.yaml";
  std::ofstream(file) << yaml;
  try {
    load_machine(file);
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected a ConfigError for:\n" << yaml;
  return "";
}

TEST(Machine, ShippedRouterFileLoadsAndDocumentsTheDefaults) {
  const MachineOptions m = load_machine(std::filesystem::path(CNCLAB_SOURCE_DIR) /
                                        "configs/machines/biaxial_router.yaml");
  EXPECT_EQ(m.name, "biaxial_router");
  const FeedDriveOptions defaults;
  const FeedDriveOptions& x = m.axes[0];
  // The x axis is the struct's defaults written out (one source of truth for
  // the numbers the docs quote).
  EXPECT_EQ(x.table_mass, defaults.table_mass);
  EXPECT_EQ(x.velocity_gain, defaults.velocity_gain);
  EXPECT_EQ(x.backlash, defaults.backlash);
  EXPECT_EQ(x.lead_error_amplitude, defaults.lead_error_amplitude);
  EXPECT_EQ(x.motor_encoder_counts, defaults.motor_encoder_counts);
  EXPECT_EQ(m.timing.integration_step, DriveTiming{}.integration_step);
  EXPECT_EQ(m.axes[1].table_mass, 40.0);
  // Both velocity loops at ~600 rad/s: Kv / J.
  for (const auto& a : m.axes) EXPECT_NEAR(a.velocity_gain / a.total_inertia(), 600.0, 6.0);
}

TEST(Machine, StrictReading) {
  std::string m = config_error("machine:\n  axes:\n    y:\n      backlash: -1\n");
  EXPECT_NE(m.find("machine.axes.y.backlash"), std::string::npos) << m;
  EXPECT_NE(m.find("must be a finite number >= 0"), std::string::npos) << m;
  EXPECT_NE(m.find("machine.yaml:4"), std::string::npos) << m;
  m = config_error("machine:\n  axes:\n    x:\n      backlsh: 0.01\n");
  EXPECT_NE(m.find("backlsh"), std::string::npos) << m;
  m = config_error("machine:\n  timing:\n    integration_step: fast\n");
  EXPECT_NE(m.find("machine.timing.integration_step"), std::string::npos) << m;
  m = config_error("machine:\n  timing:\n    integration_step: 3.0e-5\n");
  EXPECT_NE(m.find("machine.timing.integration_step = 3.0e-5: must divide velocity_loop_period"),
            std::string::npos)
      << m;
  m = config_error("machine:\n  axes:\n    x:\n      velocity_feedforward: .nan\n");
  EXPECT_NE(m.find("velocity_feedforward"), std::string::npos) << m;
  m = config_error("name: x\n");
  EXPECT_NE(m.find("machine"), std::string::npos) << m;
}

}  // namespace
}  // namespace cnclab
