// The Table 8 timing job on a small step-error experiment: it finds the test
// segments of the result on the surface (its consistency checks compare the
// exact method with the dataset's targets and the network rebuilt from the
// surface with the result's predictions), writes a standard result the
// store finds and that reads back,
// and rejects bad files and missing results.
#include "cnclab/studies/step_error/step_error_timing.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/report/tables.hpp"
#include "common/field_leaves.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

// 6 lines x 10 CC points = 54 segments of surface 2; half of them tested.
std::string small_experiment() {
  return std::string("name: small_surface2\nseed: 3\n") +
         "dataset:\n  generator: step_error\n  options:\n    surface: " CNCLAB_SOURCE_DIR
         "/configs/surfaces/surface2.yaml\n    lines: 6\n    points_per_line: 10\n"
         "split: {train: 0.5}\n"
         "normalisation: {inputs: zscore, targets: zscore}\n"
         "model: {hidden: [6], hidden_activation: relu}\n"
         "trainer: {type: sgdm, learning_rate: 1.0e-3, momentum: 0.5, batch_size: 4, epochs: 3}\n";
}

const char* kJob = R"(kind: step_error_timing
name: timing_small
experiments: {surface2: small.yaml, surface3: small.yaml}
repeats: 2
iterative: {points_per_pass: 10, relative_tolerance: 1.0e-6}
)";

TEST(StepErrorTiming, TimesTheResultsTestSegmentsAndRoundTrips) {
  TempDir dir;
  std::ofstream(dir / "small.yaml") << small_experiment();
  std::ofstream(dir / "job.yaml") << kJob;
  const StepErrorTimingJob job = load_step_error_timing_job(dir / "job.yaml");
  EXPECT_EQ(job.options.repeats, 2u);
  // No result yet: a MissingResults naming the experiment.
  EXPECT_THROW(run_step_error_timing(job, dir / "results"), MissingResults);

  RunOptions run;
  run.results_dir = dir / "results";
  run.datasets_dir = dir / "datasets";
  ASSERT_TRUE(run_experiment(load_experiment(dir / "small.yaml"), run).ok);

  // Throws if the exact errors or the rebuilt network's predictions do not
  // match the result's test targets / predictions.
  const StepErrorTimingResult r = run_step_error_timing(job, dir / "results");
  ASSERT_EQ(r.surfaces.size(), 2u);
  for (const auto& s : r.surfaces) {
    EXPECT_EQ(s.test_samples, 27u);  // 54 segments, half tested
    EXPECT_LE(s.lines, 6u);
    for (double t : {s.planning_s, s.iterative_s, s.exact_s, s.network_load_s, s.network_inputs_s,
                     s.network_forward_s}) {
      EXPECT_GT(t, 0.0);
    }
    // Iterative method at 1e-6 of the segment: far below a nanometre.
    EXPECT_LT(s.iterative_max_error_um, 1e-3);
    EXPECT_TRUE(std::isfinite(s.network_max_error_um));
  }

  // A standard result, found by the store under the job's identity; `show`
  // prints it and the timing reads back.
  const ResultStore store(dir / "results");
  const auto file = write_step_error_timing(job, r, store);
  const StoredResult stored = store.get(step_error_timing_key(job));
  EXPECT_EQ(stored.file, file);
  EXPECT_EQ(file.parent_path(), dir / "results" / "timing_small");
  EXPECT_EQ(stored.record.kind, "step_error_timing");
  ASSERT_EQ(stored.record.upstream.size(), 2u);
  EXPECT_EQ(stored.record.upstream[0].result_file, r.surfaces[0].result_file);
  const StepErrorTimingResult back = read_step_error_timing(stored.record, stored.file);
  EXPECT_EQ(back.name, r.name);
  EXPECT_EQ(back.repeats, 2u);
  ASSERT_EQ(back.surfaces.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(back.surfaces[i].surface, r.surfaces[i].surface);
    EXPECT_EQ(back.surfaces[i].test_samples, r.surfaces[i].test_samples);
    EXPECT_EQ(back.surfaces[i].result_file, r.surfaces[i].result_file);
    EXPECT_DOUBLE_EQ(back.surfaces[i].exact_s, r.surfaces[i].exact_s);
    EXPECT_DOUBLE_EQ(back.surfaces[i].network_total_s(), r.surfaces[i].network_total_s());
  }
  std::ostringstream shown;
  print_result(stored.record, shown);
  EXPECT_NE(shown.str().find("(kind: step_error_timing)"), std::string::npos) << shown.str();
  EXPECT_NE(shown.str().find("surface3.network_forward_s"), std::string::npos) << shown.str();
  // Another config (repeats) is another result: not found.
  const StepErrorTimingJob other = load_step_error_timing_job(dir / "job.yaml", {"repeats=1"});
  EXPECT_THROW(store.get(step_error_timing_key(other)), MissingResults);
}

// Every declared key of the job file changes the job's
// identity (its resolved config) and reads back from it.
TEST(StepErrorTiming, EveryJobKeyChangesTheIdentityAndRoundTrips) {
  TempDir dir;
  std::ofstream(dir / "small.yaml") << small_experiment();
  std::ofstream(dir / "job.yaml") << kJob;
  const std::string base = to_yaml(load_step_error_timing_job(dir / "job.yaml"));
  std::vector<Leaf> keys;
  leaves(step_error_timing_fields().info(), "", keys);
  ASSERT_EQ(keys.size(), 4u);
  for (const auto& leaf : keys) {
    const std::string value = other_value(leaf.info);
    ASSERT_FALSE(value.empty()) << leaf.key;
    const std::string changed =
        to_yaml(load_step_error_timing_job(dir / "job.yaml", {leaf.key + "=" + value}));
    EXPECT_NE(changed, base) << leaf.key;
    std::ofstream(dir / "again.yaml") << changed;
    EXPECT_EQ(to_yaml(load_step_error_timing_job(dir / "again.yaml")), changed) << leaf.key;
  }
}

TEST(StepErrorTiming, StrictJobFile) {
  TempDir dir;
  std::ofstream(dir / "typo.yaml") << std::string(kJob) + "repeat: 3\n";
  EXPECT_THROW(load_step_error_timing_job(dir / "typo.yaml"), ConfigError);
  std::ofstream(dir / "zero.yaml")
      << std::string(kJob).replace(std::string(kJob).find("repeats: 2"), 10, "repeats: 0");
  EXPECT_THROW(load_step_error_timing_job(dir / "zero.yaml"), ConfigError);
  std::ofstream(dir / "kind.yaml") << "kind: train\nname: x\n";
  EXPECT_THROW(load_step_error_timing_job(dir / "kind.yaml"), ConfigError);
}

}  // namespace
}  // namespace cnclab
