// The feedrate_optimisation job file: defaults round-trip through the
// resolved YAML, and bad inputs are ConfigErrors naming the key.
#include "cnclab/studies/contour_error/feedrate_job.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

fs::path write_job(const testing::TempDir& dir, const std::string& extra,
                   const std::string& predictor = "narx.yaml") {
  std::ofstream(dir.path() / "narx.yaml") << "name: n\n";  // exists: the predictor's file
  const fs::path file = dir.path() / "feedrate.yaml";
  std::ofstream(file) << "kind: feedrate_optimisation\nname: f\npredictor: " << predictor << "\n"
                      << extra;
  return file;
}

TEST(FeedrateJob, LoadsAndRoundTrips) {
  testing::TempDir dir;
  const FeedrateJob job = load_feedrate_job(
      write_job(dir,
                "tolerances: [20, 12]\nprediction_margin: 3\nsection: {start: 5}\noracle: true\n"
                "optimisation: {raise_caps: true}\n"));
  EXPECT_EQ(job.tolerances, (std::vector<double>{20, 12}));
  EXPECT_TRUE(job.oracle);
  EXPECT_TRUE(job.optimisation.raise_caps);
  EXPECT_FALSE(load_feedrate_job(write_job(dir, "")).oracle);  // off unless asked
  EXPECT_DOUBLE_EQ(job.section.start, 5.0);
  EXPECT_EQ(job.predictor_file, dir.path() / "narx.yaml");
  const fs::path again = dir.path() / "again.yaml";
  std::ofstream(again) << to_yaml(job);
  EXPECT_EQ(to_yaml(load_feedrate_job(again)), to_yaml(job));
}

TEST(FeedrateJob, BadInputsNameTheKey) {
  testing::TempDir dir;
  const auto message = [&](const std::string& extra) {
    return testing::error_message<ConfigError>([&] { load_feedrate_job(write_job(dir, extra)); });
  };
  EXPECT_NE(message("tolerances: [10, 2]\nprediction_margin: 3\n").find("tolerances"),
            std::string::npos);
  EXPECT_NE(message("tolerances: []\n").find("tolerances"), std::string::npos);
  EXPECT_NE(message("optimisation: {safety_factor: 2}\n").find("safety_factor"), std::string::npos);
  EXPECT_NE(message("optimisation: {safty_factor: 0.5}\n").find("safty_factor"), std::string::npos);
  const std::string missing = testing::error_message<ConfigError>(
      [&] { load_feedrate_job(write_job(dir, "", "missing.yaml")); });
  EXPECT_NE(missing.find("predictor"), std::string::npos) << missing;
}

}  // namespace
}  // namespace cnclab
