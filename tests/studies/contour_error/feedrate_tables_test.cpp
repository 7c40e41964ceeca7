// `cnclab tables feedrate`'s measurements over the tolerances and the
// manifest's targets (configs/studies/feedrate_tables.yaml), on a result written here with
// known metrics for the study's own experiment file: the minimum share and
// ratio are the ones put in, a plan below 99.9 % or slower than the uniform
// slowdown fails its target, and a tolerance that was not planned fails too.
#include "cnclab/studies/contour_error/feedrate_tables.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "cnclab/core/format.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/report/targets.hpp"
#include "cnclab/studies/contour_error/feedrate_job.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

struct FeedrateTablesFixture {
  testing::TempDir dir;
  TablesOptions options;
  FeedrateJob job;
  fs::path result;

  FeedrateTablesFixture() {
    options.results_dir = dir.path() / "results";
    options.experiments_dir = CNCLAB_SOURCE_DIR "/experiments";
    options.configs_dir = CNCLAB_SOURCE_DIR "/configs";
    const fs::path file = options.experiment_file("contour_error/feedrate.yaml");
    job = load_feedrate_job(file);
    result = result_path(ResultKey{job.name, std::nullopt, to_yaml(job), file, true},
                         options.results_dir);
  }

  // A result whose constrained plan at tolerance i has share_within[i] and
  // uniform / constrained time ratio[i]; NaN share: the tolerance was not
  // planned (no constrained metrics, as below_resolution writes it).
  void write(const std::vector<double>& share, const std::vector<double>& ratio) const {
    RunRecord rec = make_job_record(
        "feedrate_optimisation",
        ResultKey{job.name, std::nullopt, to_yaml(job), job.source_file, true}, job.request);
    for (std::size_t i = 0; i < job.tolerances.size(); ++i) {
      if (std::isnan(share[i])) continue;
      const std::string label = "eps" + shortest_double(job.tolerances[i]) + "um";
      rec.metrics[label + "_constrained_time"] = 1.0;
      rec.metrics[label + "_constrained_max"] = job.tolerances[i];
      rec.metrics[label + "_constrained_share_within"] = share[i];
      rec.metrics[label + "_ratio_uniform_constrained"] = ratio[i];
    }
    write_job_result(result, rec);
  }

  // Each declared target's PASS/FAIL by name.
  std::map<std::string, bool> check() const {
    std::map<std::string, bool> out;
    const auto targets =
        read_targets(options.configs_dir / "studies" / "feedrate_example_tables.yaml");
    for (const TargetResult& r :
         check_targets(targets, measure_feedrate_example_tables(options), "")) {
      out[r.target->name] = r.pass;
    }
    return out;
  }
};

TEST(FeedrateTables, MeasuresTheWorstToleranceAndChecksTheDoneWhen) {
  FeedrateTablesFixture f;
  ASSERT_EQ(f.job.tolerances.size(), 3u);  // the study's three tolerances
  f.write({1.0, 0.9995, 0.9991}, {1.16, 1.12, 1.27});
  const Measurements m = measure_feedrate_example_tables(f.options);
  EXPECT_DOUBLE_EQ(m.at("constrained.min_share_within"), 0.9991);
  EXPECT_DOUBLE_EQ(m.at("min_ratio_uniform_constrained"), 1.12);
  const auto pass = f.check();
  ASSERT_EQ(pass.size(), 2u);
  EXPECT_TRUE(pass.at("constrained.min_share_within"));
  EXPECT_TRUE(pass.at("min_ratio_uniform_constrained"));
  // The section was chosen on this outcome itself: the table's note says so.
  std::ostringstream table;
  print_feedrate_example_tables(f.options, table);
  EXPECT_NE(table.str().find("section: chosen on the reported data, not on validation"),
            std::string::npos)
      << table.str();

  f.write({1.0, 0.998, 1.0}, {1.16, 1.2, 1.27});  // one tolerance at 99.8 %
  EXPECT_FALSE(f.check().at("constrained.min_share_within"));
  f.write({1.0, 1.0, 1.0}, {1.16, 0.95, 1.27});  // slower than the uniform slowdown once
  EXPECT_FALSE(f.check().at("min_ratio_uniform_constrained"));
  f.write({1.0, NAN, 1.0}, {1.16, NAN, 1.27});  // one tolerance not planned
  const auto unplanned = f.check();
  EXPECT_FALSE(unplanned.at("constrained.min_share_within"));
  EXPECT_FALSE(unplanned.at("min_ratio_uniform_constrained"));
}

}  // namespace
}  // namespace cnclab
