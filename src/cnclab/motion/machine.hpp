#pragma once
// The simulated biaxial machine: two feed drives (x, y) sharing the loop
// timing, read from a YAML file (configs/machines/biaxial_router.yaml) through
// the strict ConfigReader, and run on a 1 ms reference trajectory.
#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>

#include "cnclab/core/config.hpp"
#include "cnclab/motion/feed_drive.hpp"
#include "cnclab/motion/interpolator.hpp"

namespace cnclab {

struct MachineOptions {
  std::string name = "biaxial_router";     // stated in results
  DriveTiming timing;                      // shared loop rates
  std::array<FeedDriveOptions, 2> axes{};  // [0] = x, [1] = y

  // Field names carry the section: "axes.y.backlash", "timing.integration_step".
  void validate() const;
};

// Reads a `machine:` section: name, timing.{...}, axes.x.{...}, axes.y.{...}
// (every key optional, defaulting to the struct's values; unknown keys are
// errors at check_all_consumed).
MachineOptions read_machine(const ConfigReader& section);
// Loads a machine file (top-level key `machine`), strict: unknown keys, wrong
// types and invalid values are ConfigErrors naming file, line and key.
MachineOptions load_machine(const std::filesystem::path& file);

struct MachineResponse {
  Eigen::MatrixX2d actual;           // tool position [mm], one row per reference sample
  Eigen::MatrixX2d measured;         // linear scale readings [mm]
  Eigen::MatrixX2d following_error;  // reference - measured [mm]
};

// Runs both axes on `reference` (its period must equal the controller
// period). The scale noise of axis x/y draws from the stream
// "feed_drive.x"/"feed_drive.y" of `seed` (core/rng.hpp).
MachineResponse simulate_machine(const MachineOptions& machine,
                                 const ReferenceTrajectory& reference, std::uint64_t seed);

}  // namespace cnclab
