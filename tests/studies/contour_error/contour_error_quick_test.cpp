// The quick profile of experiments/contour_error end to end (same code paths
// as the full study: dataset generator, both NARX studies, the tables):
// structure of the results and tables, a trained NARX that beats the zero
// predictor, and the figures drawn from the results.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>

#include "cnclab/report/targets.hpp"
#include "cnclab/studies/contour_error/contour_error_tables.hpp"
#include "cnclab/studies/contour_error/narx_study_runs.hpp"
#include "cnclab/sweep/sweep_job.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "common/temp_dir.hpp"
#include "studies/contour_error/metrics_once.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

TEST(ContourErrorQuick, ReproduceAndTables) {
  testing::TempDir dir;
  const fs::path experiments = CNCLAB_SOURCE_DIR "/experiments";
  const fs::path results = dir.path() / "results" / "quick";
  testing::register_contour_error_metrics_once();
  CommandOptions options;
  options.results_dir = results;
  options.datasets_dir = dir.path() / "datasets";
  options.profile = "quick";
  TablesOptions t;
  t.results_dir = results;
  t.experiments_dir = experiments;
  t.reference_dir = CNCLAB_SOURCE_DIR "/results/reference";
  t.profile = "quick";
  for (const char* file : {"training_methods.yaml", "architecture.yaml"}) {
    const SweepJob job = load_sweep_job(experiments / "contour_error" / file, {}, "quick");
    const SweepJobOutcome o = run_sweep_job(job, options, nullptr);
    ASSERT_TRUE(fs::exists(o.result_file)) << file;
    const NarxStudyRuns study = load_narx_study(t, file);
    EXPECT_EQ(study.runs.size(), study.trials) << file;
    for (const auto& run : study.runs) {
      // Only two-stage training (here with the windowed closed-loop start,
      // docs/narx_training.md) is claimed to work every time (seed 002 Sec.
      // II); the other methods may fail, which the tables show.
      if (run.method != "two_stage_retry") continue;
      EXPECT_TRUE(run.bounded()) << file;
      for (const std::string a : {"x", "y"}) {
        EXPECT_LT(run.metrics.at("closed_loop_rms_" + a), 0.5 * run.metrics.at("zero_rms_" + a))
            << file << " seed " << run.seed << " axis " << a;
      }
    }
  }
  std::ostringstream out;
  print_contour_error_tables(t, out);
  const std::string text = out.str();
  std::cout << text;  // the quick tables, for the test log
  for (const char* needle :
       {"training methods", "two_stage", "two_stage_retry", "open_loop_only", "closed_loop_only",
        "zero predictor", "stable: the closed-loop prediction stayed bounded", "architecture sweep",
        "<- paper's choice", "taylor", "tangent", "osculating", "Contour error predictor",
        "Paper:", "sources:"}) {
    EXPECT_NE(text.find(needle), std::string::npos) << needle << "\n" << text;
  }
  // csv and json carry numbers only: every column a number
  // column or a declared label column, read by Python's csv and json modules.
  TableEntry entry;
  entry.name = "contour-error";
  entry.print = print_contour_error_tables;
  for (const TableFormat f : {TableFormat::csv, TableFormat::json}) {
    TablesOptions machine = t;
    machine.format = f;
    std::ofstream file(dir.path() / (f == TableFormat::csv ? "tables.csv" : "tables.json"));
    print_table_document(entry, machine, file);
  }
  const std::string check_machine =
      "/usr/bin/python3 " CNCLAB_SOURCE_DIR "/tests/report/machine_tables.py '" +
      (dir.path() / "tables.csv").string() + "' '" + (dir.path() / "tables.json").string() + "'";
  EXPECT_EQ(std::system(check_machine.c_str()), 0) << check_machine;
  // The measurements count the runs the study loaded, and the targets the
  // manifest declares for the quick profile pass (`tables --check`).
  const Measurements m = measure_contour_error_tables(t);
  const NarxStudyRuns methods = load_narx_study(t, "training_methods.yaml");
  const auto retry =
      std::count_if(methods.runs.begin(), methods.runs.end(),
                    [](const NarxStudyRun& r) { return r.method == "two_stage_retry"; });
  EXPECT_EQ(m.at("training_methods.two_stage_retry.runs"), static_cast<double>(retry));
  // The predictor table counts stable runs as the methods table does (it
  // once labelled the count of bounded runs "stable").
  const std::size_t at = text.find("Contour error predictor");
  ASSERT_NE(at, std::string::npos);
  const std::string predictor = text.substr(at, text.find("Notes", at) - at);
  const std::string retry_stable =
      std::to_string(static_cast<int>(m.at("training_methods.two_stage_retry.stable_runs"))) + "/" +
      std::to_string(retry);
  const std::string row_name = "two_stage_retry";
  const std::size_t row = predictor.find(row_name);
  ASSERT_NE(row, std::string::npos) << predictor;
  const std::size_t cell = predictor.find_first_not_of(' ', row + row_name.size());
  EXPECT_EQ(predictor.substr(cell, retry_stable.size()), retry_stable) << predictor;
  t.configs_dir = CNCLAB_SOURCE_DIR "/configs";
  const auto targets = read_targets(t.configs_dir / "studies" / "contour_error_tables.yaml");
  std::size_t checked = 0;
  for (const TargetResult& r : check_targets(targets, m, "quick")) {
    if (!r.wanted) continue;
    ++checked;
    EXPECT_TRUE(r.pass) << r.target->name << ": measured " << r.measured << ", target "
                        << to_string(r.target->op) << " " << *r.wanted;
  }
  EXPECT_GT(checked, 0u);
  // The figures script draws from these results (Figs. 4, 5, 8-11, 13, 14).
  const std::string figures = "/usr/bin/python3 " CNCLAB_SOURCE_DIR
                              "/scripts/figures/contour_error.py '" +
                              results.string() + "' > /dev/null";
  ASSERT_EQ(std::system(figures.c_str()), 0) << figures;
  for (const char* png : {"fig04_toolpath.png", "fig05_velocities.png",
                          "fig08_following_error_x.png", "fig11_prediction_error_y.png",
                          "fig13_contour_error.png", "fig14_contour_prediction_error.png"}) {
    EXPECT_TRUE(fs::exists(results / "figures" / "contour_error" / png)) << png;
  }
  // A trial that ran and did not complete is named in the tables' notes, not
  // silently left out of the means: replace one trial's result by the error
  // note a crashed trial leaves.
  const SweepJob methods_job =
      load_sweep_job(experiments / "contour_error" / "training_methods.yaml", {}, "quick");
  const SweepJobState state = sweep_job_state(methods_job, results);
  const std::string lost = state.plan.trials.front().id;
  fs::remove(trial_result_path(state.dir, lost));
  std::ofstream(trial_error_path(state.dir, lost)) << "injected crash";
  const NarxStudyRuns after = load_narx_study(t, "training_methods.yaml");
  EXPECT_EQ(after.runs.size() + 1, after.trials);
  ASSERT_EQ(after.not_completed.size(), 1u);
  EXPECT_NE(after.not_completed[0].find(lost), std::string::npos) << after.not_completed[0];
  EXPECT_NE(after.not_completed[0].find("error: injected crash"), std::string::npos);
  std::ostringstream noted;
  print_contour_error_tables(t, noted);
  EXPECT_NE(
      noted.str().find("1 of " + std::to_string(after.trials) + " planned trials did not complete"),
      std::string::npos)
      << noted.str();
}

}  // namespace
}  // namespace cnclab
