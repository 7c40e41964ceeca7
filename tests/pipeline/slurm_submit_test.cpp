// The Slurm flows without a cluster (fake sbatch/squeue first on PATH,
// common/fake_slurm.hpp): reproduce's jobs wait for their upstream's jobs
// (afterok on the ids sbatch gave), current results need no job, a sweep's
// dry run lists every trial to submit, and job names are what #SBATCH takes.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <fstream>
#include <map>
#include <sstream>

#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/pipeline/reproduce_slurm.hpp"
#include "cnclab/pipeline/slurm_sweep_submit.hpp"
#include "common/fake_slurm.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// PATH with the fake clients first, restored afterwards.
class FakeSlurmPath {
 public:
  explicit FakeSlurmPath(const fs::path& dir) : old_(getenv("PATH") ? getenv("PATH") : "") {
    testing::fake_slurm(dir);
    setenv("PATH", ((dir / "bin").string() + ":/usr/bin:/bin").c_str(), 1);
  }
  ~FakeSlurmPath() { setenv("PATH", old_.c_str(), 1); }

 private:
  std::string old_;
};

void write_experiments(const fs::path& dir) {
  std::ofstream(dir / "a.yaml") << "include: " << testing::kSlurmTestExperiment
                                << "\nname: a\ntrainer: {epochs: 2}\n"
                                   "dataset: {options: {samples: 200}}\n";
  std::ofstream(dir / "b.yaml") << "include: a.yaml\nname: b\nneeds: [a.yaml]\n";
  std::ofstream(dir / "d.yaml") << "include: a.yaml\nname: d\n";
}

CommandOptions options_in(const TempDir& tmp) {
  CommandOptions o;
  o.results_dir = tmp / "results";
  o.datasets_dir = tmp / "data";
  o.quiet = true;
  return o;
}

TEST(SlurmJobName, OnlyCharactersAnSbatchLineKeeps) {
  EXPECT_EQ(slurm_job_name("a b/c.d", "-merge"), "cnclab-a_b_c_d-merge");
  EXPECT_EQ(slurm_job_name("x-1_y", ""), "cnclab-x-1_y");
}

TEST(ReproduceSlurm, JobsWaitForTheirUpstreamsJobIds) {
  TempDir tmp;
  write_experiments(tmp.path());
  FakeSlurmPath path(tmp.path());
  ReproduceInputs inputs;
  for (const char* f : {"a", "b", "d"}) inputs.files.push_back(tmp / (f + std::string(".yaml")));
  SlurmOptions slurm;
  std::ostringstream out, log;
  const ReproduceSlurmRun run = submit_reproduce_slurm(inputs, options_in(tmp), slurm, out, log);
  EXPECT_EQ(run.exit_code, 0);
  EXPECT_EQ(run.submitted, 3u);
  std::map<std::string, ReproduceSlurmRow> rows;
  for (const auto& r : run.rows) rows[r.name] = r;
  // The fake sbatch answers 100, 101, ... in submission order (graph order).
  EXPECT_EQ(rows["a"].job, "100");
  EXPECT_EQ(rows["a"].after, "");
  EXPECT_EQ(rows["b"].after, rows["a"].job);
  EXPECT_EQ(rows["d"].after, "");
  std::ifstream calls(tmp / "calls.txt");
  const std::string text((std::istreambuf_iterator<char>(calls)), {});
  EXPECT_NE(text.find("--dependency=afterok:" + rows["a"].job + " "), std::string::npos) << text;
}

TEST(ReproduceSlurm, DryRunNamesJobsAndSubmitsNothing) {
  TempDir tmp;
  write_experiments(tmp.path());
  FakeSlurmPath path(tmp.path());
  ReproduceInputs inputs;
  for (const char* f : {"a", "b"}) inputs.files.push_back(tmp / (f + std::string(".yaml")));
  SlurmOptions slurm;
  slurm.dry_run = true;
  std::ostringstream out, log;
  const ReproduceSlurmRun run = submit_reproduce_slurm(inputs, options_in(tmp), slurm, out, log);
  ASSERT_EQ(run.rows.size(), 2u);
  EXPECT_EQ(run.rows[0].action, "submit");
  EXPECT_EQ(run.rows[1].job, "{b}");
  EXPECT_EQ(run.rows[1].after, "{a}");
  EXPECT_EQ(run.submitted, 0u);
  EXPECT_FALSE(fs::exists(tmp / "calls.txt"));
  EXPECT_FALSE(fs::exists(tmp / "results"));
  EXPECT_NE(out.str().find("#SBATCH"), std::string::npos);
}

TEST(SweepSlurm, DryRunListsEveryTrialToSubmit) {
  TempDir tmp;
  write_experiments(tmp.path());
  FakeSlurmPath path(tmp.path());
  SweepCommandOptions o;
  o.common = options_in(tmp);
  SlurmOptions slurm;
  slurm.dry_run = true;
  std::ostringstream out, log;
  const SweepSlurmResult r =
      submit_sweep_slurm(tmp / "a.yaml", {"trainer.learning_rate=0.001,0.01,0.1"}, std::nullopt, o,
                         slurm, {}, out, log);
  EXPECT_EQ(r.total, 3u);
  EXPECT_EQ(r.to_submit, 3u);
  EXPECT_EQ(r.done + r.in_flight, 0u);
  EXPECT_NE(out.str().find("3 of 3 trials to submit"), std::string::npos) << out.str();
  EXPECT_FALSE(fs::exists(tmp / "calls.txt"));
}

}  // namespace
}  // namespace cnclab
