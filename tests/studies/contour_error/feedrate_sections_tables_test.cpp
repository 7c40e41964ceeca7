// `cnclab tables feedrate`'s measurements over declared sections
// (feedrate_sections_tables.hpp) and the manifest's targets, on results
// written here with known per-section figures for the study's own job
// files: counts, medians, minima and the share of the oracle's gain are the
// ones worked out by hand below, and each "Done when" target fails when its
// figure is one step on the wrong side.
#include "cnclab/studies/contour_error/feedrate_sections_tables.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "cnclab/experiment/job_result.hpp"
#include "cnclab/report/targets.hpp"
#include "cnclab/studies/contour_error/feedrate_job.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

struct SectionsFixture {
  testing::TempDir dir;
  TablesOptions options;

  SectionsFixture() {
    options.results_dir = dir.path() / "results";
    options.experiments_dir = CNCLAB_SOURCE_DIR "/experiments";
    options.configs_dir = CNCLAB_SOURCE_DIR "/configs";
  }

  // Every section and tolerance at share `share` and ratios `ratio`
  // (uniform / constrained) and `oracle` (uniform / oracle), then
  // `change(rec)`.
  void write(const char* file, double share, double ratio, double oracle,
             const std::function<void(RunRecord&, const FeedrateJob&)>& change = {}) const {
    const fs::path path = options.experiment_file(file);
    const FeedrateJob job = load_feedrate_job(path);
    const ResultKey key{job.name, std::nullopt, to_yaml(job), path, true};
    RunRecord rec = make_job_record("feedrate_optimisation", key, job.request);
    for (std::size_t k = 0; k < job.sections.count; ++k) {
      const std::string s = feedrate_section_prefix(job, k);
      rec.metrics[s + "start"] = 100.0 * static_cast<double>(k);
      for (const double tol : job.tolerances) {
        const std::string p = s + feedrate_tolerance_label(tol) + "_";
        rec.metrics[p + "constrained_share_within"] = share;
        rec.metrics[p + "ratio_uniform_constrained"] = ratio;
        rec.metrics[p + "ratio_uniform_oracle"] = oracle;
      }
    }
    rec.metrics["calibration_slowed_rms"] = 3.0;
    rec.metrics["calibration_slowed_underprediction_p99"] = 4.0;
    rec.metrics["compare0_slowed_rms"] = 5.0;
    rec.facts["compare0_name"] = "other";
    rec.facts["compare0_inputs"] = "v_x";
    if (change) change(rec, job);
    write_job_result(result_path(key, options.results_dir), rec);
  }

  std::map<std::string, bool> check() const {
    std::map<std::string, bool> out;
    const auto targets = read_targets(options.configs_dir / "studies" / "feedrate_tables.yaml");
    for (const TargetResult& r :
         check_targets(targets, measure_feedrate_sections_tables(options), "")) {
      out[r.target->name] = r.pass;
    }
    return out;
  }
};

TEST(FeedrateSectionsTables, MeasuresEveryDeclaredSection) {
  SectionsFixture f;
  // Validation path: section 3 misses 99.9 % at 20 um (99.7 %), section 5 is
  // 3 % slower than the uniform slowdown at 25 um; the ratios otherwise
  // 1.10, the oracle's 1.125: 80 % of its gain.
  f.write("contour_error/any_path/feedrate_sections.yaml", 1.0, 1.10, 1.125,
          [](RunRecord& r, const FeedrateJob&) {
            r.metrics["s03_eps20um_constrained_share_within"] = 0.997;
            r.metrics["s05_eps25um_ratio_uniform_constrained"] = 0.97;
            // Margins of two bands, and of two after a change of direction.
            r.metrics["calibration_margin_band0"] = 6.5;
            r.metrics["calibration_margin_band1"] = 11.5;
            r.metrics["calibration_margin_after_reversal_band0"] = 13.25;
            r.metrics["calibration_margin_after_reversal_band1"] = 8.0;
            r.facts["calibration_inputs"] = "v_x, direction_x";
          });
  f.write("contour_error/any_path/feedrate_unseen_path.yaml", 0.9995, 1.05, 1.04);
  const Measurements m = measure_feedrate_sections_tables(f.options);
  EXPECT_EQ(m.at("validation_path.sections"), 15.0);
  EXPECT_EQ(m.at("validation_path.sections_meeting_all"), 14.0);
  EXPECT_EQ(m.at("validation_path.eps20um.sections_meeting"), 14.0);
  EXPECT_EQ(m.at("validation_path.eps30um.sections_meeting"), 15.0);
  EXPECT_DOUBLE_EQ(m.at("validation_path.min_share_within"), 0.997);
  EXPECT_DOUBLE_EQ(m.at("validation_path.eps20um.median_share_within"), 1.0);
  EXPECT_DOUBLE_EQ(m.at("validation_path.min_ratio_uniform_constrained"), 0.97);
  EXPECT_DOUBLE_EQ(m.at("validation_path.eps25um.median_ratio_uniform_constrained"), 1.10);
  EXPECT_NEAR(m.at("validation_path.eps25um.oracle_gain_share"), 0.8, 1e-12);
  // Unseen path: the oracle gains 4 %, the plan 5 %: more than all of it.
  EXPECT_NEAR(m.at("unseen_path.min_oracle_gain_share"), 1.25, 1e-12);
  EXPECT_EQ(m.at("predictor.lowest_slowed_rms"), 1.0);
  EXPECT_EQ(m.at("predictor.max_margin_um"), 13.25);  // the largest of either class
  const auto pass = f.check();
  EXPECT_TRUE(pass.at("validation_path.sections_meeting_all"));
  EXPECT_TRUE(pass.at("validation_path.min_share_within"));
  EXPECT_FALSE(pass.at("validation_path.min_ratio_uniform_constrained"));  // 0.97 < 1/1.02
  EXPECT_TRUE(pass.at("validation_path.min_oracle_gain_share"));
  EXPECT_TRUE(pass.at("unseen_path.sections_meeting_all"));
  EXPECT_TRUE(pass.at("predictor.lowest_slowed_rms"));

  std::ostringstream out;
  print_feedrate_sections_tables(f.options, out);
  EXPECT_NE(out.str().find("15 sections of the validation half"), std::string::npos) << out.str();
  EXPECT_NE(out.str().find("14/15"), std::string::npos);
  // The job declares a 50 ms reversal window: its margins are listed, and
  // the planning predictor's inputs.
  EXPECT_NE(out.str().find("within 50 ms of a change of direction of either axis: 13.25 µm"),
            std::string::npos)
      << out.str();
  EXPECT_NE(out.str().find("v_x, direction_x"), std::string::npos);
}

TEST(FeedrateSectionsTables, MissesFailTheirTargets) {
  SectionsFixture f;
  // Two sections below 99.9 %, one of them below 99.5 %; a compared
  // predictor with a lower held-out RMS; the oracle's gain missed.
  f.write("contour_error/any_path/feedrate_sections.yaml", 1.0, 1.05, 1.20,
          [](RunRecord& r, const FeedrateJob&) {
            r.metrics["s01_eps30um_constrained_share_within"] = 0.998;
            r.metrics["s02_eps20um_constrained_share_within"] = 0.99;
            r.metrics["compare0_slowed_rms"] = 2.0;
          });
  f.write("contour_error/any_path/feedrate_unseen_path.yaml", 1.0, 1.05, 1.05,
          [](RunRecord& r, const FeedrateJob&) {
            r.facts.erase("s04_eps20um_status");
            // A tolerance not planned on a section: nothing promised there.
            r.metrics.erase("s04_eps20um_constrained_share_within");
            r.metrics.erase("s04_eps20um_ratio_uniform_constrained");
          });
  const Measurements m = measure_feedrate_sections_tables(f.options);
  EXPECT_EQ(m.at("validation_path.sections_meeting_all"), 13.0);
  EXPECT_NEAR(m.at("validation_path.min_oracle_gain_share"), 0.25, 1e-12);
  EXPECT_EQ(m.at("unseen_path.sections_meeting_all"), 14.0);
  EXPECT_EQ(m.at("unseen_path.min_share_within"), 0.0);
  EXPECT_TRUE(std::isnan(m.at("unseen_path.min_ratio_uniform_constrained")));
  const auto pass = f.check();
  EXPECT_FALSE(pass.at("validation_path.sections_meeting_all"));
  EXPECT_FALSE(pass.at("validation_path.min_share_within"));
  EXPECT_FALSE(pass.at("validation_path.min_oracle_gain_share"));
  EXPECT_FALSE(pass.at("unseen_path.min_share_within"));
  EXPECT_FALSE(pass.at("unseen_path.min_ratio_uniform_constrained"));
  EXPECT_FALSE(pass.at("predictor.lowest_slowed_rms"));
}

// One path run, the other not: the table says which is missing before any
// number, and the missing path's targets (and the predictor comparison,
// declared by the validation-half job) fail instead of passing by absence.
TEST(FeedrateSectionsTables, APathNotRunIsNamedAndFailsItsTargets) {
  SectionsFixture f;
  f.write("contour_error/any_path/feedrate_unseen_path.yaml", 1.0, 1.05, 1.05);
  std::ostringstream out;
  print_feedrate_sections_tables(f.options, out);
  const std::string text = out.str();
  EXPECT_LT(text.find("not shown"), text.find("15 sections"));
  EXPECT_NE(text.find("feedrate_sections.yaml"), std::string::npos) << text;
  const Measurements m = measure_feedrate_sections_tables(f.options);
  EXPECT_EQ(m.at("unseen_path.sections"), 15.0);
  EXPECT_TRUE(std::isnan(m.at("validation_path.sections")));
  const auto pass = f.check();
  EXPECT_TRUE(pass.at("unseen_path.sections_meeting_all"));
  EXPECT_FALSE(pass.at("validation_path.sections"));
  EXPECT_FALSE(pass.at("validation_path.sections_meeting_all"));
  EXPECT_FALSE(pass.at("predictor.lowest_slowed_rms"));
}

TEST(FeedrateSectionsTables, NothingRunIsMissingResultsNamingTheCommand) {
  SectionsFixture f;
  try {
    measure_feedrate_sections_tables(f.options);
    FAIL() << "no error";
  } catch (const MissingResults& e) {
    EXPECT_NE(std::string(e.what()).find("cnclab reproduce experiments/contour_error/any_path"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace cnclab
