// A job's result file (job_result.hpp) in the standard format: written,
// read back through read_result and read_result_status (the readers every
// command uses) field by field, and printed by print_result (`cnclab show`).
#include "cnclab/experiment/job_result.hpp"

#include <gtest/gtest.h>

#include <sstream>
#include <stdexcept>

#include "cnclab/core/hash.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

TEST(JobResult, RoundTripsThroughTheResultReaders) {
  TempDir dir;
  const ResultKey key{"groove", std::nullopt, "kind: gcode\nname: groove\nstep: 1.5\n",
                      dir / "groove.yaml", false};
  RunRecord r = make_job_record("gcode", key, {{"step=1.5"}, "quick"});
  r.metrics = {{"points", 1234}, {"max_engagement_deg", 97.5}};
  r.outputs = {{"program", "groove.nc"}, {"report", "groove-report.txt"}};
  r.upstream = {{"up.yaml", "results/up/up-seed1-0123abcd.h5", "fedcba9876543210"}};
  r.facts = {{"selected_trial", "t0003"}};
  const auto file = result_path(key, dir / "results");
  EXPECT_EQ(file, dir / "results/groove" /
                      ("groove-" + hash_hex(key.resolved_yaml).substr(0, 8) + ".h5"));
  write_job_result(file, r);

  const RunRecord back = read_result(file);
  EXPECT_EQ(back.kind, "gcode");
  EXPECT_EQ(back.experiment, "groove");
  EXPECT_EQ(back.resolved_yaml, key.resolved_yaml);
  EXPECT_EQ(back.config_hash, hash_hex(key.resolved_yaml));
  EXPECT_EQ(back.provenance.status, "complete");
  EXPECT_EQ(back.metrics, r.metrics);
  ASSERT_EQ(back.outputs.size(), 2u);
  EXPECT_EQ(back.outputs[1].role, "report");
  EXPECT_EQ(back.outputs[1].file, "groove-report.txt");
  EXPECT_EQ(output_path(back, file, "program"), file.parent_path() / "groove.nc");
  EXPECT_THROW(output_path(back, file, "points"), IoError);
  ASSERT_EQ(back.upstream.size(), 1u);
  EXPECT_EQ(back.upstream[0].identity, "fedcba9876543210");
  EXPECT_EQ(back.facts, r.facts);
  EXPECT_EQ(back.provenance.overrides, std::vector<std::string>{"step=1.5"});
  EXPECT_EQ(back.provenance.profile, "quick");

  const ResultStatus status = read_result_status(file);
  EXPECT_EQ(status.status, "complete");
  EXPECT_EQ(status.metrics, r.metrics);

  std::ostringstream shown;
  print_result(back, shown);
  for (const char* part : {"experiment   groove (kind: gcode)", "output       program: groove.nc",
                           "  points", "  step: 1.5", "fact         selected_trial: t0003",
                           "override     step=1.5", "profile      quick"}) {
    EXPECT_NE(shown.str().find(part), std::string::npos) << part << "\n" << shown.str();
  }

  // The store finds it by its key like any result.
  EXPECT_EQ(ResultStore(dir / "results").get(key).record.metrics, r.metrics);
}

TEST(JobResult, RefusesTrainingRecords) {
  TempDir dir;
  RunRecord r;
  EXPECT_THROW(write_job_result(dir / "x.h5", r), std::logic_error);
}

}  // namespace
}  // namespace cnclab
