// A `kind: sweep` job (sweep_job.hpp) on tiny IK networks: the selected
// trial is the one with the least validation MSE, found here from the trial
// result files and from summary.h5 read directly; a second run reuses the
// finished sweep (nothing re-run, files untouched); bad job files are
// ConfigErrors that write nothing.
#include "cnclab/sweep/sweep_job.hpp"

#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/job_result.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/train/sgdm.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;

const char* kIkExperiment = R"(name: ik_tiny
seed: 8
dataset: {generator: ik_samples, targets: [X], options: {values_per_input: 3}}
split: {train_count: 120, test_count: 60}
normalisation: {inputs: minmax, targets: minmax, target_range: [0.1, 0.9]}
model: {hidden: [5, 4], hidden_activation: sigmoid, output_activation: sigmoid}
trainer: {type: sgdm, learning_rate: 0.3, momentum: 0.5, epochs: 40}
metrics: [mse, normalised_mse, normalised_validation_mse]
)";

const char* kJob = R"(kind: sweep
name: tiny_search
experiment: ik_tiny.yaml
overrides: [trainer.epochs=5]
jobs: 2
sweep:
  method: random
  trials: 5
  seed: 3
  objective: {metric: normalised_validation_mse, mode: min}
  parameters:
    model.hidden: [[3, 2], [6, 4]]
    trainer.learning_rate: uniform(0.05, 0.9)
    trainer.momentum: uniform(0.0, 0.8)
)";

class SweepJobTest : public ::testing::Test {
 protected:
  void SetUp() override {
    write("ik_tiny.yaml", kIkExperiment);
    write("search.yaml", kJob);
    options_.results_dir = dir_ / "results";
    options_.datasets_dir = dir_ / "datasets";
    options_.quiet = true;
  }
  void write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
  }
  SweepJobOutcome run(bool force = false) {
    CommandOptions o = options_;
    o.force = force;
    return run_sweep_job(load_sweep_job(dir_ / "search.yaml"), o, nullptr);
  }
  testing::TempDir dir_;
  CommandOptions options_;
};

TEST_F(SweepJobTest, SelectsTheTrialWithTheLeastValidationMse) {
  const SweepJobOutcome r = run();
  ASSERT_EQ(r.stopped, 0);
  EXPECT_EQ(r.ran, 5u);
  const SweepJobState& s = r.state;
  ASSERT_TRUE(s.finished());
  ASSERT_EQ(s.summary.complete, 5u);
  EXPECT_EQ(s.dir, dir_ / "results/tiny_search" / ("sweep-" + s.plan.hash().substr(0, 8)));

  // From the trial result files.
  std::string best_id;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& entry : fs::directory_iterator(s.dir / "trials")) {
    if (entry.path().extension() != ".h5") continue;
    const RunRecord rec = read_result(entry.path());
    const double v = rec.metrics.at("validation.normalised_mse");
    ASSERT_TRUE(std::isfinite(v));
    EXPECT_EQ(rec.trainer, "sgdm");
    if (v < best) best = v, best_id = entry.path().stem().string();
  }
  ASSERT_FALSE(best_id.empty());
  ASSERT_TRUE(s.selected);
  EXPECT_EQ(s.plan.trials[*s.selected].id, best_id);

  // From summary.h5, read directly.
  const H5File f = H5File::open_read(s.dir / "summary.h5");
  const auto ids = f.read_strings("/trials/id");
  const auto vals = f.read_vector("/trials/metrics/validation.normalised_mse");
  ASSERT_EQ(ids.size(), 5u);
  std::size_t argmin = 0;
  for (std::size_t i = 1; i < vals.size(); ++i) {
    if (vals[i] < vals[argmin]) argmin = i;
  }
  EXPECT_EQ(ids[argmin], best_id);
  EXPECT_EQ(vals[argmin], best);

  // selection.yaml names the same trial, its parameters and metrics.
  const YAML::Node sel = YAML::LoadFile((dir_ / "results/tiny_search/selection.yaml").string());
  EXPECT_EQ(sel["selected"]["trial"].as<std::string>(), best_id);
  EXPECT_EQ(sel["selected"]["metrics"]["validation.normalised_mse"].as<double>(), best);
  const RunRecord chosen = read_result(s.selected_result());
  EXPECT_EQ(sel["selected"]["parameters"]["trainer.learning_rate"].as<double>(),
            trainer_options<SgdmOptions>(s.plan.trials[*s.selected].experiment->spec.trainer)
                .learning_rate);
  EXPECT_EQ(sel["selected"]["parameters"]["model.hidden"].as<std::vector<std::size_t>>(),
            chosen.model.hidden);
  // The fixed override reached every trial.
  EXPECT_EQ(chosen.training.history.size(), 5u);

  // The selection as a standard result: found by the store under the job's
  // key, naming the same trial (its metrics, its file beside it).
  const SweepJob job = load_sweep_job(dir_ / "search.yaml");
  const StoredResult stored = ResultStore(dir_ / "results").get(sweep_job_key(job, s.plan));
  EXPECT_EQ(stored.file, r.result_file);
  EXPECT_EQ(stored.record.kind, "sweep");
  EXPECT_EQ(stored.record.facts.at("selected_trial"), best_id);
  EXPECT_EQ(stored.record.metrics.at("validation.normalised_mse"), best);
  EXPECT_EQ(stored.record.metrics.at("sweep.complete"), 5.0);
  EXPECT_EQ(output_path(stored.record, stored.file, "selected_trial"), s.selected_result());
}

TEST_F(SweepJobTest, SecondRunReusesTheFinishedSweep) {
  const SweepJobOutcome first = run();
  ASSERT_EQ(first.ran, 5u);
  std::map<fs::path, fs::file_time_type> times;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "results")) {
    if (e.is_regular_file()) times[e.path()] = fs::last_write_time(e.path());
  }
  const SweepJobOutcome second = run();
  EXPECT_EQ(second.ran, 0u);
  ASSERT_TRUE(second.state.selected);
  EXPECT_EQ(second.state.plan.trials[*second.state.selected].id,
            first.state.plan.trials[*first.state.selected].id);
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir_ / "results")) {
    if (!e.is_regular_file()) continue;
    ++files;
    EXPECT_EQ(fs::last_write_time(e.path()), times.at(e.path())) << e.path();
  }
  EXPECT_EQ(files, times.size());

  // A changed plan is another sweep folder; --force runs every trial again.
  EXPECT_EQ(run(true).ran, 5u);
  write("search.yaml", std::string(kJob) + "    trainer.shuffle: [true, false]\n");
  const SweepJobOutcome changed = run();
  EXPECT_NE(changed.state.dir, first.state.dir);
  // Its trials whose config the first sweep trained are taken from the
  // result store (sweep_execute.cpp); only the others run.
  std::set<std::string> trained;
  for (const auto& t : first.state.plan.trials) trained.insert(t.id);
  std::size_t known = 0;
  for (const auto& t : changed.state.plan.trials) known += trained.count(t.id);
  EXPECT_GT(known, 0u);
  EXPECT_EQ(changed.ran, changed.state.plan.trials.size() - known);
  EXPECT_TRUE(changed.state.finished());
}

TEST_F(SweepJobTest, BadJobFilesAreConfigErrors) {
  const auto expect_error = [&](const std::string& text, const std::string& fragment) {
    write("bad.yaml", text);
    try {
      load_sweep_job(dir_ / "bad.yaml");
      ADD_FAILURE() << "no error for " << text;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
    }
  };
  const std::string job = kJob;
  expect_error(job + "jobz: 2\n", "jobz");
  expect_error(
      "kind: sweep\nname: s\nexperiment: nosuch.yaml\nsweep: {parameters: {seed: [1, 2]}}\n",
      "no experiment file");
  expect_error("kind: sweep\nname: s\nexperiment: ik_tiny.yaml\nsweep: {}\n", "no parameters");
  expect_error(
      "kind: sweep\nname: s\nexperiment: ik_tiny.yaml\noverrides: [epochs]\n"
      "sweep: {parameters: {seed: [1, 2]}}\n",
      "overrides");
  // An objective the experiment does not compute stops before any trial.
  write("obj.yaml",
        "kind: sweep\nname: s\nexperiment: ik_tiny.yaml\n"
        "sweep: {objective: {metric: r2}, parameters: {seed: [1, 2]}}\n");
  EXPECT_THROW(run_sweep_job(load_sweep_job(dir_ / "obj.yaml"), options_, nullptr), ConfigError);
  EXPECT_FALSE(fs::exists(dir_ / "results"));
}

}  // namespace
}  // namespace cnclab
