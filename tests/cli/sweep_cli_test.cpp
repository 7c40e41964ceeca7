// End-to-end tests of `cnclab sweep`, `sweep merge`, `compare` and the
// experiment graph in `reproduce`, on real processes: trial results identical
// with 1 and 2 jobs and with shards, resume after SIGKILL / SIGINT / SIGTERM
// of a running sweep with nothing lost or duplicated, failure isolation, and
// bad sweep specs as usage errors. Independent checks: h5diff (hdf5-tools)
// compares files; trial contents are compared with the uninterrupted
// reference sweep.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <thread>

#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::slurp;
using testing::TempDir;

const std::string kCnclab = CNCLAB_BINARY_DIR "/cnclab";
const std::string kExperiment = CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_mlp.yaml";

using Result = testing::ShellResult;

Result sh(const fs::path& dir, const std::string& command) {
  return testing::run_shell(dir, command);
}

// Small, fast trials: 3 keep probabilities x 2 learning rates.
std::string sweep_args(const std::string& extra, const std::string& epochs = "20") {
  return kExperiment + " trainer.epochs=" + epochs +
         " dataset.options.samples=300 model.hidden=[16,8] "
         "model.dropout.keep_probability=0.8,0.9,1.0 "
         "trainer.learning_rate=1e-3,1e-2 --quiet --data-dir data " +
         extra;
}

std::vector<fs::path> trial_files(const fs::path& dir) {
  std::vector<fs::path> out;
  if (!fs::exists(dir / "trials")) return out;
  for (const auto& e : fs::directory_iterator(dir / "trials")) {
    if (e.path().extension() == ".h5" && !is_partial_path(e.path())) out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

// The trial results of two sweep folders agree bit for bit in everything a
// trial computes (times and hosts in /provenance aside).
void expect_same_trials(const fs::path& a, const fs::path& b) {
  const auto fa = trial_files(a), fb = trial_files(b);
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t i = 0; i < fa.size(); ++i) {
    ASSERT_EQ(fa[i].filename(), fb[i].filename());
    const RunRecord ra = read_result(fa[i]), rb = read_result(fb[i]);
    EXPECT_EQ(ra.resolved_yaml, rb.resolved_yaml);
    EXPECT_EQ(ra.parameters, rb.parameters) << fa[i];
    EXPECT_EQ(ra.test_predictions, rb.test_predictions) << fa[i];
    EXPECT_EQ(ra.metrics, rb.metrics) << fa[i];
  }
}

// `cnclab run` of one point of sweep_args (keep 0.9, learning rate 1e-2) into r/.
Result run_one_point(const fs::path& dir) {
  return sh(dir, kCnclab + " run " + kExperiment +
                     " trainer.epochs=20 dataset.options.samples=300 "
                     "model.hidden=[16,8] model.dropout.keep_probability=0.9 "
                     "trainer.learning_rate=1e-2 --quiet --data-dir data --out r");
}

const std::string kNoTimes = " --exclude-path /provenance --exclude-path /history/wall_seconds ";

TEST(SweepCli, TwoJobsGiveBitIdenticalTrialsToOneJob) {
  TempDir dir;
  const Result one = sh(dir.path(), kCnclab + " sweep " + sweep_args("--jobs 1 --dir one"));
  ASSERT_EQ(one.code, 0) << one.err << one.out;
  // Its own results folder: with the first one's, every trial would be taken
  // from the result store instead of trained.
  const Result two =
      sh(dir.path(), kCnclab + " sweep " + sweep_args("--jobs 2 --dir two --out results-two"));
  ASSERT_EQ(two.code, 0) << two.err << two.out;
  ASSERT_EQ(trial_files(dir / "one").size(), 6u);
  expect_same_trials(dir / "one", dir / "two");
  for (const auto& f : trial_files(dir / "one")) {
    const Result d = sh(dir.path(), "h5diff" + kNoTimes + f.string() + " " +
                                        (dir / "two/trials" / f.filename()).string());
    EXPECT_EQ(d.code, 0) << d.out << d.err;
  }
  // A trial is the plain run of its config: `cnclab run` with the same
  // overrides writes the same numbers.
  const Result run = run_one_point(dir.path());
  ASSERT_EQ(run.code, 0) << run.err;
  const RunRecord plain = read_result(dir / run.out.substr(0, run.out.find('\n')));
  bool found = false;
  for (const auto& f : trial_files(dir / "one")) {
    const RunRecord t = read_result(f);
    if (t.config_hash == plain.config_hash) {
      found = true;
      EXPECT_EQ(t.parameters, plain.parameters);
      EXPECT_EQ(f.stem().string(), plain.config_hash);  // identity = hash of the resolved config
    }
  }
  EXPECT_TRUE(found);
  // The summary table is ranked by the objective (mse, min by default).
  EXPECT_NE(one.out.find("6 complete, 0 failed"), std::string::npos) << one.out;
}

// Config groups. `trainer=NAME` replaces the block with
// configs/trainers/NAME.yaml (finer overrides apply after it, wherever they
// stand), so a sweep can compare trainers; a missing group name is exit 2
// naming the fragments there are.
TEST(SweepCli, ConfigGroupsReplaceTheTrainerBlockAndCanBeSwept) {
  TempDir dir;
  const Result v = sh(dir.path(), kCnclab + " validate " + kExperiment + " trainer=trainbr");
  ASSERT_EQ(v.code, 0) << v.err;
  EXPECT_NE(v.out.find("trainer:\n  type: trainbr\n  epochs: 1000\n  goal: 0\n  mu: 0.005"),
            std::string::npos)
      << v.out;
  EXPECT_EQ(v.out.find("learning_rate"), std::string::npos) << v.out;
  const Result s = sh(dir.path(), kCnclab + " sweep " + kExperiment +
                                      " trainer=sgdm_minibatch,trainbr trainer.epochs=2 "
                                      "dataset.options.samples=120 model.hidden=[4] --quiet "
                                      "--data-dir data --dir s --jobs 1");
  ASSERT_EQ(s.code, 0) << s.err << s.out;
  ASSERT_EQ(trial_files(dir / "s").size(), 2u);
  std::set<std::string> types;
  for (const auto& f : trial_files(dir / "s")) {
    const RunRecord r = read_result(f);
    types.insert(r.trainer);
    EXPECT_NE(r.resolved_yaml.find("epochs: 2\n"), std::string::npos) << r.resolved_yaml;
  }
  EXPECT_EQ(types, (std::set<std::string>{"sgdm", "trainbr"}));
  const Result bad = sh(dir.path(), kCnclab + " validate " + kExperiment + " trainer=adam");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("no config group file configs/trainers/adam.yaml"), std::string::npos)
      << bad.err;
  EXPECT_NE(bad.err.find("trainbr.yaml"), std::string::npos) << bad.err;
}

TEST(SweepCli, RerunSkipsCompleteTrials) {
  TempDir dir;
  ASSERT_EQ(sh(dir.path(), kCnclab + " sweep " + sweep_args("--jobs 2 --dir s")).code, 0);
  const auto before = fs::last_write_time(trial_files(dir / "s")[0]);
  const Result again =
      sh(dir.path(), kCnclab + " sweep " + sweep_args("--jobs 2 --dir s").substr(0) + " ");
  ASSERT_EQ(again.code, 0);
  const Result verbose =
      sh(dir.path(), kCnclab + " sweep " + kExperiment +
                         " trainer.epochs=20 dataset.options.samples=300 "
                         "model.hidden=[16,8] "
                         "model.dropout.keep_probability=0.8,0.9,1.0 "
                         "trainer.learning_rate=1e-3,1e-2 --data-dir data --dir s");
  EXPECT_NE(verbose.err.find("6 already done, running 0"), std::string::npos) << verbose.err;
  EXPECT_EQ(fs::last_write_time(trial_files(dir / "s")[0]), before);
}

// A trial is the run of its config: a sweep takes a complete result `cnclab
// run` made for the same config instead of training, and publishes the
// trials it trains where `cnclab run` would write them, so a second sweep over
// the same points (another sweep folder) trains nothing.
TEST(SweepCli, TrialsShareResultsWithTheResultStore) {
  TempDir dir;
  const Result run = run_one_point(dir.path());
  ASSERT_EQ(run.code, 0) << run.err;
  const fs::path plain = dir / run.out.substr(0, run.out.find('\n'));
  const std::string plain_bytes = slurp(plain);
  // Without --quiet: the sweep's header line says what it took.
  const auto verbose_sweep = [&](const std::string& folder) {
    std::string args = sweep_args("--jobs 2 --dir " + folder + " --out r");
    args.erase(args.find(" --quiet"), 8);
    return sh(dir.path(), kCnclab + " sweep " + args);
  };

  const Result first = verbose_sweep("s");
  ASSERT_EQ(first.code, 0) << first.err << first.out;
  EXPECT_NE(first.err.find("1 taken from the results store; 1 already done, running 5"),
            std::string::npos)
      << first.err;
  const auto trials = trial_files(dir / "s");
  ASSERT_EQ(trials.size(), 6u);
  std::size_t published = 0;
  for (const auto& f : trials) {
    const RunRecord t = read_result(f);
    EXPECT_EQ(f.stem().string(), t.config_hash);
    // Where `cnclab run` writes this config: <out>/<name>/<name>-seed<s>-<8 hex>.h5
    std::vector<fs::path> stored;
    for (const auto& e : fs::directory_iterator(dir / "r/friedman1_mlp")) {
      const std::string name = e.path().filename().string();
      if (name.ends_with("-" + t.config_hash.substr(0, 8) + ".h5")) stored.push_back(e.path());
    }
    ASSERT_EQ(stored.size(), 1u) << f;
    EXPECT_EQ(slurp(stored[0]), slurp(f)) << f;
    if (stored[0] == plain) {
      EXPECT_EQ(slurp(f), plain_bytes);  // taken, not trained again
    } else {
      ++published;
    }
  }
  EXPECT_EQ(published, 5u);
  EXPECT_EQ(slurp(plain), plain_bytes);  // never replaced

  // Another sweep folder over the same points trains nothing.
  const Result again = verbose_sweep("s2");
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.err.find("6 taken from the results store; 6 already done, running 0"),
            std::string::npos)
      << again.err;
  expect_same_trials(dir / "s", dir / "s2");
}

// Starts a sweep, waits until `done_before_kill` trials have results, sends
// `sig`, and returns the exit status.
int interrupt_sweep(const fs::path& dir, const std::string& sweep_dir, int sig,
                    std::size_t done_before_kill) {
  std::vector<std::string> args = {kCnclab,
                                   "sweep",
                                   kExperiment,
                                   "trainer.epochs=100",
                                   "dataset.options.samples=500",
                                   "model.dropout.keep_probability=0.7,0.8,0.9,1.0",
                                   "trainer.learning_rate=1e-3,1e-2",
                                   "--jobs",
                                   "2",
                                   "--quiet",
                                   "--data-dir",
                                   (dir / "data").string(),
                                   "--dir",
                                   (dir / sweep_dir).string(),
                                   "--out",
                                   (dir / (sweep_dir + "-results")).string()};
  const pid_t pid = testing::spawn_quiet(args);
  if (pid <= 0) return -1;  // never kill(-1, ...)
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (trial_files(dir / sweep_dir).size() < done_before_kill &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  kill(pid, sig);
  return testing::wait_exit(pid);
}

void expect_resume_completes(const fs::path& dir, const std::string& sweep_dir, int sig,
                             int expected_status) {
  const int status = interrupt_sweep(dir, sweep_dir, sig, 2);
  EXPECT_EQ(status, expected_status);
  // Children die with the sweep: nothing appears afterwards.
  const std::size_t after_kill = trial_files(dir / sweep_dir).size();
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  EXPECT_EQ(trial_files(dir / sweep_dir).size(), after_kill) << "a trial outlived its sweep";
  EXPECT_GE(after_kill, 2u);
  EXPECT_LT(after_kill, 8u) << "the kill came too late to interrupt anything";

  const Result resume =
      sh(dir, kCnclab + " sweep " + kExperiment +
                  " trainer.epochs=100 dataset.options.samples=500 "
                  "model.dropout.keep_probability=0.7,0.8,0.9,1.0 trainer.learning_rate=1e-3,1e-2 "
                  "--jobs 2 --data-dir data --dir " +
                  sweep_dir + " --out " + sweep_dir + "-results");
  ASSERT_EQ(resume.code, 0) << resume.err << resume.out;
  EXPECT_NE(resume.err.find(std::to_string(after_kill) + " already done, running " +
                            std::to_string(8 - after_kill)),
            std::string::npos)
      << resume.err;
  EXPECT_NE(resume.out.find("8 complete, 0 failed"), std::string::npos) << resume.out;
  // Exactly one result per trial, each equal to the uninterrupted sweep's.
  EXPECT_EQ(trial_files(dir / sweep_dir).size(), 8u);
  expect_same_trials(dir / "reference", dir / sweep_dir);
}

class SweepKill : public ::testing::Test {
 protected:
  // One reference sweep for the suite (TempDir needs a running test).
  static void SetUpTestSuite() {
    dir_ = new fs::path(fs::temp_directory_path() /
                        ("cnclab_SweepKill_" + std::to_string(::getpid())));
    fs::remove_all(*dir_);
    fs::create_directories(*dir_);
    const Result ref =
        sh(*dir_, kCnclab + " sweep " + kExperiment +
                      " trainer.epochs=100 dataset.options.samples=500 "
                      "model.dropout.keep_probability=0.7,0.8,0.9,1.0 "
                      "trainer.learning_rate=1e-3,1e-2 --jobs 2 --quiet --data-dir data "
                      "--dir reference --out reference-results");
    ASSERT_EQ(ref.code, 0) << ref.err;
  }
  static void TearDownTestSuite() {
    fs::remove_all(*dir_);
    delete dir_;
  }
  static fs::path* dir_;
};
fs::path* SweepKill::dir_ = nullptr;

TEST_F(SweepKill, ResumeAfterKill9LosesAndDuplicatesNothing) {
  expect_resume_completes(*dir_, "killed", SIGKILL, -SIGKILL);
}

TEST_F(SweepKill, ResumeAfterSigint) {
  expect_resume_completes(*dir_, "sigint", SIGINT, 128 + SIGINT);
}

TEST_F(SweepKill, ResumeAfterSigterm) {
  expect_resume_completes(*dir_, "sigterm", SIGTERM, 128 + SIGTERM);
}

TEST(SweepCli, DivergingTrialIsRecordedAsFailedAndTheSweepGoesOn) {
  TempDir dir;
  const Result r = sh(dir.path(), kCnclab + " sweep " + kExperiment +
                                      " trainer.epochs=5 dataset.options.samples=200 "
                                      "trainer.learning_rate=1e-3,1e12,1e-2 --jobs 2 --dir s");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("2 complete, 1 failed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("FAILED trial"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("diverged"), std::string::npos) << r.out;
  // The summary counts it (h5dump reads the attributes independently).
  const Result dump = sh(dir.path(), "h5dump -a /failed s/summary.h5");
  EXPECT_NE(dump.out.find("(0): 1"), std::string::npos) << dump.out;
  // Ranked: the failed point is last.
  const auto last_row = r.out.find("3     1e12");
  EXPECT_NE(last_row, std::string::npos) << r.out;
}

TEST(SweepCli, ThrowingTrialIsRecordedWithItsReasonAndRetriedOnResume) {
  TempDir dir;
  // 1e8 samples of 10000 inputs cannot fit in memory: that trial throws a
  // ResourceError in its process.
  const std::string sweep = kCnclab + " sweep " + kExperiment +
                            " trainer.epochs=3 'dataset.options={samples: 200},{samples: "
                            "100000000, inputs: 10000}' --jobs 2 --data-dir data --dir s";
  const Result r = sh(dir.path(), sweep);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("1 complete, 1 failed"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("needs about"), std::string::npos) << r.out;
  std::size_t notes = 0;
  for (const auto& e : fs::directory_iterator(dir / "s/trials")) {
    if (e.path().extension() == ".error") {
      ++notes;
      EXPECT_NE(slurp(e.path()).find("TiB"), std::string::npos);
    }
  }
  EXPECT_EQ(notes, 1u);
  EXPECT_EQ(trial_files(dir / "s").size(), 1u);
  // No result, so a re-run tries it again (the error may have been transient).
  const Result again = sh(dir.path(), sweep);
  EXPECT_NE(again.err.find("1 already done, running 1"), std::string::npos) << again.err;
  const Result dump = sh(dir.path(), "h5dump -d /trials/status s/summary.h5");
  EXPECT_NE(dump.out.find("\"error"), std::string::npos) << dump.out;
}

TEST(SweepCli, TrialTimeoutKillsTheTrialAndRecordsItAsFailed) {
  TempDir dir;
  // 1 epoch against 10^6 (minutes): the second trial runs into the timeout.
  const std::string sweep = kCnclab + " sweep " + kExperiment +
                            " trainer.epochs=1,1000000 dataset.options.samples=200 --jobs 2 "
                            "--data-dir data --dir s --trial-timeout 2";
  const auto start = std::chrono::steady_clock::now();
  const Result r = sh(dir.path(), sweep);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_LT(seconds, 60.0);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("1 complete, 1 failed"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("failed: timeout: killed after running longer than 2 s"), std::string::npos)
      << r.err;
  EXPECT_EQ(trial_files(dir / "s").size(), 1u);  // no result of the killed trial
  // Failed, not an error: a resume leaves it alone...
  const Result resume = sh(dir.path(), sweep);
  EXPECT_NE(resume.err.find("2 already done, running 0"), std::string::npos) << resume.err;
  // ...unless asked to retry failed trials.
  const Result retry = sh(dir.path(), sweep + " --retry-failed");
  EXPECT_NE(retry.err.find("1 already done, running 1"), std::string::npos) << retry.err;
  EXPECT_NE(sh(dir.path(), kCnclab + " sweep " + kExperiment + " --trial-timeout 0")
                .err.find("--trial-timeout"),
            std::string::npos);
}

TEST(SweepCli, ShardsThenMergeEqualAnUnshardedSweep) {
  TempDir dir;
  ASSERT_EQ(sh(dir.path(), kCnclab + " sweep " + sweep_args("--jobs 2 --dir whole")).code, 0);
  for (const char* shard : {"1/3", "2/3", "3/3"}) {
    const Result r =
        sh(dir.path(), kCnclab + " sweep " +
                           sweep_args(std::string("--jobs 1 --dir sharded --out results-sharded "
                                                  "--shard ") +
                                      shard));
    ASSERT_EQ(r.code, 0) << shard << r.err << r.out;
    EXPECT_NE(r.out.find("2 complete"), std::string::npos) << r.out;  // 6 trials / 3 shards
  }
  EXPECT_FALSE(fs::exists(dir / "sharded/summary.h5"));
  const Result merge = sh(dir.path(), kCnclab + " sweep merge sharded");
  ASSERT_EQ(merge.code, 0) << merge.err << merge.out;
  expect_same_trials(dir / "whole", dir / "sharded");
  const Result d = sh(dir.path(), "h5diff whole/summary.h5 sharded/summary.h5");
  EXPECT_EQ(d.code, 0) << d.out << d.err;
  // A sweep folder compares its trials in plan order: the swept keys differ.
  const Result c = sh(dir.path(), kCnclab + " compare whole --format csv");
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_NE(c.out.find("kind,key,[1],[2],[3],[4],[5],[6],"), std::string::npos) << c.out;
  EXPECT_NE(c.out.find("config,model.dropout.keep_probability,0.8,0.8,0.9,0.9,1,1,"),
            std::string::npos)
      << c.out;
}

// `cnclab show summary.h5` prints the ranking as `sweep
// merge` prints it (without the merge's "summary:" line), rewriting nothing.
// One point has all weights 0 and no training step: its trials are complete
// and warned.
TEST(SweepCli, ShowSummaryPrintsTheMergeRankingAndWritesNothing) {
  TempDir dir;
  const Result sweep = sh(dir.path(), kCnclab + " sweep " + kExperiment +
                                          " trainer.epochs=0 dataset.options.samples=200 "
                                          "model.init.weights.type=normal "
                                          "model.init.weights.std=0,1 --quiet --data-dir data "
                                          "--dir s");
  ASSERT_EQ(sweep.code, 0) << sweep.err << sweep.out;
  EXPECT_NE(sweep.out.find("): constant predictions\n"), std::string::npos) << sweep.out;
  EXPECT_NE(sweep.out.find("1/1, 1 warning"), std::string::npos) << sweep.out;
  const Result merge = sh(dir.path(), kCnclab + " sweep merge s");
  ASSERT_EQ(merge.code, 0) << merge.err;
  const std::string before = slurp(dir / "s/summary.h5");
  const auto mtime = fs::last_write_time(dir / "s/summary.h5");
  const Result show = sh(dir.path(), kCnclab + " show s/summary.h5");
  ASSERT_EQ(show.code, 0) << show.err;
  EXPECT_EQ(show.out + "summary: s/summary.h5\n", merge.out);
  EXPECT_EQ(slurp(dir / "s/summary.h5"), before);
  EXPECT_EQ(fs::last_write_time(dir / "s/summary.h5"), mtime);
}

TEST(SweepCli, MergeReportsMissingShards) {
  TempDir dir;
  ASSERT_EQ(sh(dir.path(), kCnclab + " sweep " + sweep_args("--dir s --shard 1/2")).code, 0);
  const Result merge = sh(dir.path(), kCnclab + " sweep merge s");
  EXPECT_EQ(merge.code, 1);
  EXPECT_NE(merge.out.find("3 trial(s) have no result yet"), std::string::npos) << merge.out;
}

void expect_usage_error(const Result& r, const std::string& fragment) {
  EXPECT_EQ(r.code, 2) << r.err << r.out;
  EXPECT_NE(r.err.find(fragment), std::string::npos) << r.err;
}

TEST(SweepCli, BadSweepSpecsAreUsageErrorsAndRunNothing) {
  TempDir dir;
  const std::string base = kCnclab + " sweep " + kExperiment + " --dir s ";
  expect_usage_error(sh(dir.path(), base + "trainer.momentm=0.1,0.2"),
                     "trainer.momentm: unknown key (did you mean 'momentum'?)");
  expect_usage_error(sh(dir.path(), base + "trainer.momentum=,"), "empty value in the list");
  expect_usage_error(sh(dir.path(), base + "'trainer.momentum=choice()'"),
                     "choice() needs at least one value");
  expect_usage_error(sh(dir.path(), base + "'trainer.learning_rate=log_uniform(0,1)' --trials 3"),
                     "log_uniform needs 0 < low");
  expect_usage_error(sh(dir.path(), base + "'trainer.learning_rate=log_uniform(-1,1)' --trials 3"),
                     "log_uniform needs 0 < low");
  expect_usage_error(sh(dir.path(), base + "trainer.momentum=0.1,0.2 --shard 3/2"),
                     "--shard 3/2: K must be between 1 and N");
  expect_usage_error(sh(dir.path(), base + "trainer.momentum=0.1,0.2 --shard 0/2"),
                     "K must be between 1 and N");
  expect_usage_error(
      sh(dir.path(), base + "'trainer.learning_rate=uniform(0.1,0.2)' --method grid"),
      "a grid cannot enumerate a continuous distribution");
  expect_usage_error(sh(dir.path(), base + "'trainer.learning_rate=uniform(0.1,0.2)'"),
                     "random search needs a number of trials");
  expect_usage_error(
      sh(dir.path(), base + "trainer.momentum=0.1,0.2 --objective accuracy"),
      "objective metric 'validation.accuracy' is not among the experiment's metrics");
  expect_usage_error(sh(dir.path(), base + "trainer.momentum=0.1,1.5"), "must be in [0, 1)");
  expect_usage_error(sh(dir.path(), base + "trainer.epochs=3"), "no parameters to vary");
  EXPECT_FALSE(fs::exists(dir / "s"));
}

TEST(SweepCli, SweepBlockInTheExperimentFile) {
  TempDir dir;
  std::ofstream(dir / "exp.yaml") << "include: " << kExperiment << R"(
trainer: {epochs: 5}
dataset: {options: {samples: 200}}
sweep:
  method: random
  trials: 4
  repeats: 2
  objective: {metric: rmse, mode: min}
  parameters:
    trainer.learning_rate: log_uniform(1e-3, 1e-1)
    model.hidden: [[8], [16, 8]]
)";
  const Result r = sh(dir.path(), kCnclab + " sweep exp.yaml --jobs 2 --dir s");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("8 trials (4 points x 2 repeats, random)"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("validation.rmse [1] (min)"), std::string::npos)
      << r.out;                                              // rmse: validation
  EXPECT_NE(r.out.find(" ± "), std::string::npos) << r.out;  // mean ± std over repeats
  // `compare --group-by repeats`: the 4 points, 2 seeds each.
  const Result g = sh(dir.path(), kCnclab + " compare s --group-by repeats --format csv");
  ASSERT_EQ(g.code, 0) << g.err << g.out;
  EXPECT_EQ(g.out.substr(0, g.out.find('\n')),
            "metric,stratum,group,n,mean,std,ci_low,ci_high,ci_clipped,diff,welch_t,welch_df,"
            "welch_p,boot_low,boot_high,pairs,paired_t,paired_p,wilcoxon_w,wilcoxon_p,test,"
            "significant");
  const Result j = sh(dir.path(), kCnclab + " compare s --group-by repeats --format json");
  ASSERT_EQ(j.code, 0) << j.err;
  const auto count = [&](const std::string& word) {
    std::size_t n = 0;
    for (auto at = j.out.find(word); at != std::string::npos; at = j.out.find(word, at + 1)) ++n;
    return n;
  };
  EXPECT_EQ(count("\"label\":"), 9u) << j.out;  // the 4 points; 1 stratum and its 4 groups
  EXPECT_EQ(count("\"n\": 2,"), count("\"metric\":")) << j.out;  // 2 repeats each
  const Result h = sh(dir.path(), kCnclab + " compare s --group-by model.hidden --format json");
  ASSERT_EQ(h.code, 0) << h.err;
  EXPECT_NE(h.out.find("\"label\": \"model.hidden=[8]\""), std::string::npos) << h.out;
  expect_usage_error(sh(dir.path(), kCnclab + " compare s --group-by model.hiden"),
                     "did you mean 'model.hidden'");
  // `cnclab run` of the same file runs its base configuration.
  EXPECT_EQ(sh(dir.path(), kCnclab + " run exp.yaml --quiet --out r").code, 0);
  // A typo inside the block names the file position.
  std::ofstream(dir / "bad.yaml") << "include: " << kExperiment
                                  << "\nsweep:\n  repeets: 2\n  parameters: {seed: [1, 2]}\n";
  expect_usage_error(sh(dir.path(), kCnclab + " sweep bad.yaml"),
                     "bad.yaml:3:12: sweep.repeets: unknown key (did you mean 'repeats'?)");
}

// `cnclab sweep FILE` of a `kind: sweep` file names the sweep (the file's
// `name:`) beside the experiment it sweeps, in the summary's header and in
// the Slurm job names; a plain experiment's sweep names the experiment.
TEST(SweepCli, SweepFileIsNamedByItsOwnName) {
  TempDir dir;
  std::ofstream(dir / "search.yaml")
      << "kind: sweep\nname: lr_search\nexperiment: " << kExperiment
      << "\noverrides: [trainer.epochs=2, dataset.options.samples=200, 'model.hidden=[8]']\n"
         "sweep: {parameters: {trainer.learning_rate: [0.001, 0.01]}}\n";
  const Result slurm = sh(dir.path(), kCnclab + " sweep search.yaml --out r --slurm --dry-run");
  ASSERT_EQ(slurm.code, 0) << slurm.err;
  EXPECT_NE(slurm.out.find("#SBATCH --job-name=cnclab-lr_search\n"), std::string::npos)
      << slurm.out;
  const Result r = sh(dir.path(), kCnclab + " sweep search.yaml --jobs 2 --quiet --out r");
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("== sweep lr_search (experiment friedman1_mlp): 2 trials"),
            std::string::npos)
      << r.out;
  const Result plain = sh(dir.path(), kCnclab + " sweep " + kExperiment +
                                          " trainer.epochs=2 dataset.options.samples=200 "
                                          "model.hidden=[8] seed=1,2 --quiet --out r --dir p");
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_NE(plain.out.find("== sweep friedman1_mlp: 2 trials"), std::string::npos) << plain.out;
}

TEST(CompareCli, TwoKnownRunsShowOnlyDifferingKeysAndMetricDeltas) {
  TempDir dir;
  const std::string run = kCnclab + " run " + kExperiment +
                          " trainer.epochs=5 dataset.options.samples=200 --quiet --data-dir d ";
  const Result a = sh(dir.path(), run + "--out a");
  const Result b = sh(dir.path(), run + "trainer.learning_rate=1e-3 --out b");
  ASSERT_EQ(a.code, 0);
  ASSERT_EQ(b.code, 0);
  const std::string fa = a.out.substr(0, a.out.find('\n'));
  const std::string fb = b.out.substr(0, b.out.find('\n'));
  const RunRecord ra = read_result(dir / fa), rb = read_result(dir / fb);
  const Result csv = sh(dir.path(), kCnclab + " compare " + fa + " b --format csv");
  ASSERT_EQ(csv.code, 0) << csv.err;
  std::istringstream lines(csv.out);
  std::string line;
  std::getline(lines, line);
  EXPECT_EQ(line, "kind,key,[1],[2],delta [2]-[1]");
  std::getline(lines, line);
  EXPECT_EQ(line, "config,trainer.learning_rate,0.01,0.001,");  // the only differing key
  std::size_t metric_rows = 0;
  while (std::getline(lines, line)) {
    ASSERT_EQ(line.rfind("metric,", 0), 0u) << line;
    const std::string name = line.substr(7, line.find(',', 7) - 7);
    std::vector<double> cells;
    std::istringstream cs(line.substr(line.find(',', 7) + 1));
    for (std::string cell; std::getline(cs, cell, ',');) cells.push_back(std::stod(cell));
    ASSERT_EQ(cells.size(), 3u);
    EXPECT_EQ(cells[0], ra.metrics.at(name));  // shortest round-trip text
    EXPECT_EQ(cells[1], rb.metrics.at(name));
    EXPECT_EQ(cells[2], rb.metrics.at(name) - ra.metrics.at(name));
    ++metric_rows;
  }
  EXPECT_EQ(metric_rows, ra.metrics.size());
  const Result table = sh(dir.path(), kCnclab + " compare " + fa + " " + fb);
  EXPECT_NE(table.out.find("trainer.learning_rate"), std::string::npos);
  EXPECT_EQ(table.out.find("trainer.momentum"), std::string::npos) << table.out;
  const Result md = sh(dir.path(), kCnclab + " compare " + fa + " " + fb + " --format md");
  EXPECT_NE(md.out.find("| trainer.learning_rate | 0.01 | 0.001 |"), std::string::npos) << md.out;
  const Result json = sh(dir.path(), kCnclab + " compare " + fa + " " + fb + " --format json");
  EXPECT_NE(json.out.find("\"trainer.learning_rate\": [\"0.01\", \"0.001\"]"), std::string::npos)
      << json.out;
  expect_usage_error(sh(dir.path(), kCnclab + " compare " + fa), "needs at least two runs");
  expect_usage_error(sh(dir.path(), kCnclab + " compare " + fa + " " + fb + " --format xml"),
                     "--format xml");
}

TEST(CompareCli, RunsOfDifferentExperimentsShowMissingKeys) {
  TempDir dir;
  std::ofstream(dir / "up.yaml") << "include: " << kExperiment
                                 << "\nname: up\ntrainer: {epochs: 3}\ndataset: {options: "
                                    "{samples: 200}}\n";
  std::ofstream(dir / "down.yaml") << "include: up.yaml\nname: down\ninit_from: {experiment: "
                                      "up.yaml}\n";
  ASSERT_EQ(sh(dir.path(), kCnclab + " reproduce down.yaml --quiet").code, 0);
  const Result r = sh(dir.path(), kCnclab + " compare results/up results/down");
  ASSERT_EQ(r.code, 0) << r.err;
  // The key [1] does not have shows as "—" (the columns are as wide as the
  // longest metric name).
  const auto row = r.out.find("init_from.experiment ");
  ASSERT_NE(row, std::string::npos) << r.out;
  const std::string line = r.out.substr(row, r.out.find('\n', row) - row);
  EXPECT_NE(line.find(" — "), std::string::npos) << line;
  EXPECT_NE(line.find("up.yaml"), std::string::npos) << line;
  EXPECT_NE(r.out.find("name "), std::string::npos) << r.out;
}

// up.yaml: a small upstream experiment; `epochs` changes its result.
void write_upstream(const fs::path& dir, int epochs) {
  std::ofstream(dir / "up.yaml") << "include: " << kExperiment
                                 << "\nname: up\ntrainer: {epochs: " << epochs
                                 << "}\ndataset: {options: {samples: 200}}\n";
}

TEST(GraphCli, ReproduceRunsUpstreamFirstAndReusesUntilUpstreamChanges) {
  TempDir dir;
  const auto write_up = [&](int epochs) { write_upstream(dir.path(), epochs); };
  write_up(3);
  // Fine-tuning with a vanishing learning rate keeps the upstream weights
  // exactly, so the downstream predictions must equal the upstream's.
  std::ofstream(dir / "down.yaml") << "include: up.yaml\nname: down\ntrainer: {epochs: 1, "
                                      "learning_rate: 1e-300}\ninit_from: {experiment: up.yaml}\n";
  std::ofstream(dir / "side.yaml") << "include: " << kExperiment
                                   << "\nname: side\ntrainer: {epochs: 2}\ndataset: {options: "
                                      "{samples: 200}}\nneeds: [up.yaml]\n";
  const std::string reproduce = kCnclab + " reproduce down.yaml side.yaml --quiet";
  const Result first = sh(dir.path(), reproduce);
  ASSERT_EQ(first.code, 0) << first.err << first.out;
  EXPECT_LT(first.out.find("up "), first.out.find("down ")) << first.out;  // upstream first
  EXPECT_NE(first.out.find("ran          no result for this resolved config yet"),
            std::string::npos)
      << first.out;
  const Result second = sh(dir.path(), reproduce);
  ASSERT_EQ(second.code, 0);
  EXPECT_EQ(second.out.find("ran "), std::string::npos) << second.out;
  EXPECT_NE(second.out.find("reused       config and upstream results unchanged"),
            std::string::npos);

  write_up(4);  // an upstream change
  const Result third = sh(dir.path(), reproduce);
  ASSERT_EQ(third.code, 0) << third.out;
  EXPECT_NE(third.out.find("down                         ran          upstream up changed"),
            std::string::npos)
      << third.out;
  EXPECT_NE(third.out.find("side                         ran          upstream up changed"),
            std::string::npos)
      << third.out;
  std::vector<fs::path> up_files, down_files;
  for (const auto& e : fs::directory_iterator(dir / "results/up")) up_files.push_back(e.path());
  for (const auto& e : fs::directory_iterator(dir / "results/down")) down_files.push_back(e.path());
  ASSERT_EQ(down_files.size(), 1u);
  const RunRecord down = read_result(down_files[0]);
  bool matched = false;
  for (const auto& f : up_files) {
    const RunRecord up = read_result(f);
    if (up.resolved_yaml.find("epochs: 4") == std::string::npos) continue;
    matched = true;
    EXPECT_EQ(down.parameters, up.parameters);  // started from the new upstream model
    ASSERT_EQ(down.upstream.size(), 1u);
  }
  EXPECT_TRUE(matched);

  // A different network cannot start from the upstream parameters.
  std::ofstream(dir / "wrong.yaml") << "include: up.yaml\nname: wrong\nmodel: {hidden: [8]}\n"
                                       "init_from: {experiment: up.yaml}\n";
  const Result wrong = sh(dir.path(), kCnclab + " reproduce wrong.yaml --quiet");
  EXPECT_EQ(wrong.code, 2);
  EXPECT_NE(wrong.out.find("holds a network 10-64-32-1 (tanh/linear) but this experiment builds "
                           "10-8-1 (tanh/linear)"),
            std::string::npos)
      << wrong.out;
  // A cycle is a usage error naming the files.
  std::ofstream(dir / "c1.yaml") << "include: up.yaml\nname: c1\nneeds: [c2.yaml]\n";
  std::ofstream(dir / "c2.yaml") << "include: up.yaml\nname: c2\nneeds: [c1.yaml]\n";
  const Result cycle = sh(dir.path(), kCnclab + " reproduce c1.yaml --quiet");
  EXPECT_EQ(cycle.code, 2);
  EXPECT_NE(cycle.err.find("cycle"), std::string::npos) << cycle.err;
}

// A diamond a -> {b, c} -> d with 2 jobs: b and c wait for a, d for both;
// every result equals the one-job run bit for bit, and d records the results
// of b and c it started from.
// A `kind: sweep` job runs after the graph, but its dataset is generated
// in a free slot while the graph trains: the log says so
// before the graph's run ends, the job then finds it cached, and the
// results equal a --jobs 1 run's.
TEST(GraphCli, ReproduceGeneratesAJobsDatasetBesideTheTraining) {
  TempDir tmp;
  const fs::path one = tmp / "one", two = tmp / "two";
  for (const fs::path& dir : {one, two}) {
    fs::create_directories(dir);
    write_upstream(dir, 3);
    std::ofstream(dir / "swept.yaml") << "include: " << kExperiment
                                      << "\nname: swept\ntrainer: {epochs: 2}\n"
                                         "dataset: {options: {samples: 300}}\n";
    std::ofstream(dir / "search.yaml")
        << "kind: sweep\nname: search\nexperiment: swept.yaml\njobs: 1\n"
           "sweep: {parameters: {trainer.learning_rate: [0.01, 0.02]}}\n";
  }
  const Result serial = sh(one, kCnclab + " reproduce up.yaml search.yaml --jobs 1");
  ASSERT_EQ(serial.code, 0) << serial.err << serial.out;
  const Result parallel = sh(two, kCnclab + " reproduce up.yaml search.yaml --jobs 2");
  ASSERT_EQ(parallel.code, 0) << parallel.err << parallel.out;
  const std::string& log = parallel.err;
  const auto prepare = log.find("[prepare] dataset friedman1-");
  ASSERT_NE(prepare, std::string::npos) << log;
  EXPECT_NE(log.find("(search), beside the training"), std::string::npos) << log;
  EXPECT_LT(prepare, log.find("] up ran in")) << log;
  EXPECT_NE(log.find("[prepared] dataset friedman1-"), std::string::npos) << log;
  // One file per dataset: the graph's and the job's.
  std::size_t datasets = 0;
  for (const auto& e : fs::directory_iterator(two / "datasets")) {
    datasets += e.path().extension() == ".h5";
  }
  EXPECT_EQ(datasets, 2u);
  const auto trials = [](const fs::path& dir) {
    for (const auto& e : fs::directory_iterator(dir / "results" / "search")) {
      if (e.path().filename().string().rfind("sweep-", 0) == 0) return trial_files(e.path());
    }
    return std::vector<fs::path>{};
  };
  const auto a = trials(one), b = trials(two);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_EQ(b.size(), 2u);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].filename(), b[i].filename());
    EXPECT_EQ(read_result(a[i]).test_predictions, read_result(b[i]).test_predictions) << a[i];
  }
}

TEST(GraphCli, ParallelReproduceWaitsForUpstreamAndMatchesOneJob) {
  TempDir tmp;
  const fs::path one = tmp / "one", two = tmp / "two";
  for (const fs::path& dir : {one, two}) {
    fs::create_directories(dir);
    write_upstream(dir, 3);
    std::ofstream(dir / "b.yaml")
        << "include: up.yaml\nname: b\ninit_from: {experiment: up.yaml}\n";
    std::ofstream(dir / "c.yaml") << "include: up.yaml\nname: c\ntrainer: {epochs: 2}\n"
                                     "init_from: {experiment: up.yaml}\n";
    std::ofstream(dir / "d.yaml") << "include: up.yaml\nname: d\nneeds: [b.yaml, c.yaml]\n";
  }
  const Result serial = sh(one, kCnclab + " reproduce d.yaml --jobs 1");
  ASSERT_EQ(serial.code, 0) << serial.err << serial.out;
  const Result parallel = sh(two, kCnclab + " reproduce d.yaml --jobs 2");
  ASSERT_EQ(parallel.code, 0) << parallel.err << parallel.out;
  EXPECT_NE(parallel.err.find("training up to 2 at once"), std::string::npos) << parallel.err;
  // The log says when each run starts and ends: up ends before b and c
  // start, and d starts after both ended.
  const std::string& log = parallel.err;
  const auto at = [&](const std::string& text) {
    const auto pos = log.find(text);
    EXPECT_NE(pos, std::string::npos) << text << " in\n" << log;
    return pos;
  };
  const auto up_done = at("] up (upstream) ran in");
  EXPECT_LT(up_done, at("] b (upstream) (no result"));
  EXPECT_LT(up_done, at("] c (upstream) (no result"));
  EXPECT_LT(at("] b (upstream) ran in"), at("] d (no result"));
  EXPECT_LT(at("] c (upstream) ran in"), at("] d (no result"));

  const auto result_of = [](const fs::path& dir, const std::string& name) {
    const fs::path folder = dir / "results" / name;
    std::vector<fs::path> files;
    for (const auto& e : fs::directory_iterator(folder)) files.push_back(e.path());
    EXPECT_EQ(files.size(), 1u) << folder;  // and no error note left behind
    return read_result(files.at(0));
  };
  for (const std::string name : {"up", "b", "c", "d"}) {
    const RunRecord a = result_of(one, name), b = result_of(two, name);
    EXPECT_EQ(a.resolved_yaml, b.resolved_yaml) << name;
    EXPECT_EQ(a.parameters, b.parameters) << name;
    EXPECT_EQ(a.test_predictions, b.test_predictions) << name;
  }
  const RunRecord d = result_of(two, "d");
  ASSERT_EQ(d.upstream.size(), 2u);
  EXPECT_EQ(d.upstream[0].identity, result_identity(result_of(two, "b")));
  EXPECT_EQ(d.upstream[1].identity, result_identity(result_of(two, "c")));
  // Everything current: nothing runs.
  const Result again = sh(two, kCnclab + " reproduce d.yaml --jobs 2 --quiet");
  EXPECT_EQ(again.out.find("ran "), std::string::npos) << again.out;
}

// A diverged training fails `run` and `reproduce` (exit 1) unless the
// experiment says `may_diverge: true`; the result records the divergence
// either way.
TEST(GraphCli, MayDivergeMakesADivergedRunAResult) {
  TempDir dir;
  std::ofstream(dir / "blowup.yaml") << "include: " << kExperiment
                                     << "\nname: blowup\ndataset: {options: {samples: 200}}\n"
                                        "model: {hidden_activation: relu}\n"
                                        "trainer: {epochs: 5, learning_rate: 1e6}\n";
  std::ofstream(dir / "allowed.yaml") << "include: blowup.yaml\nname: allowed\nmay_diverge: true\n";
  const Result failed = sh(dir.path(), kCnclab + " reproduce blowup.yaml --quiet");
  EXPECT_EQ(failed.code, 1) << failed.out;
  EXPECT_NE(failed.out.find("ran, FAILED"), std::string::npos) << failed.out;
  EXPECT_EQ(sh(dir.path(), kCnclab + " run blowup.yaml --quiet").code, 1);

  const Result allowed = sh(dir.path(), kCnclab + " reproduce allowed.yaml --quiet");
  EXPECT_EQ(allowed.code, 0) << allowed.out;
  EXPECT_NE(allowed.out.find("ran, diverged"), std::string::npos) << allowed.out;
  EXPECT_NE(allowed.out.find("(allowed: may_diverge)"), std::string::npos) << allowed.out;
  const Result reused = sh(dir.path(), kCnclab + " reproduce allowed.yaml --quiet");
  EXPECT_EQ(reused.code, 0);
  EXPECT_NE(reused.out.find("reused, diverged"), std::string::npos) << reused.out;
  const Result run = sh(dir.path(), kCnclab + " run allowed.yaml --quiet");
  EXPECT_EQ(run.code, 0) << run.out;
  EXPECT_NE(run.out.find("diverged"), std::string::npos) << run.out;
  EXPECT_NE(sh(dir.path(), kCnclab + " validate allowed.yaml").out.find("may_diverge: true"),
            std::string::npos);
}

TEST(GraphCli, SweepTrialsRunAgainWhenTheirUpstreamChanged) {
  TempDir dir;
  const auto write_up = [&](int epochs) { write_upstream(dir.path(), epochs); };
  write_up(3);
  std::ofstream(dir / "down.yaml") << "include: up.yaml\nname: down\ninit_from: {experiment: "
                                      "up.yaml}\n";
  ASSERT_EQ(sh(dir.path(), kCnclab + " reproduce up.yaml --quiet").code, 0);
  const std::string sweep = kCnclab + " sweep down.yaml trainer.epochs=1,2 --dir s";
  ASSERT_EQ(sh(dir.path(), sweep).code, 0);
  EXPECT_NE(sh(dir.path(), sweep).err.find("2 already done, running 0"), std::string::npos);
  write_up(4);
  ASSERT_EQ(sh(dir.path(), kCnclab + " reproduce up.yaml --quiet").code, 0);
  const Result again = sh(dir.path(), sweep);
  EXPECT_EQ(again.code, 0) << again.err;
  EXPECT_NE(again.err.find("2 to run again (upstream results changed); 0 already done, running 2"),
            std::string::npos)
      << again.err;
}

TEST(GraphCli, ANewDatasetGeneratorVersionMakesAResultStale) {
  TempDir dir;
  std::ofstream(dir / "e.yaml") << "include: " << kExperiment
                                << "\nname: e\ntrainer: {epochs: 2}\ndataset: {options: "
                                   "{samples: 200}}\n";
  const Result first = sh(dir.path(), kCnclab + " reproduce e.yaml --quiet");
  ASSERT_EQ(first.code, 0) << first.err;
  // Pretend the result was made from another generator version's dataset
  // (its cache file name carries the version).
  const fs::path file =
      dir / "results/e" / fs::directory_iterator(dir / "results/e")->path().filename();
  RunRecord r = read_result(file);
  r.dataset_file = "datasets/friedman1-0123456789abcdef.h5";
  write_result(file, r);
  const Result again = sh(dir.path(), kCnclab + " reproduce e.yaml --quiet");
  EXPECT_NE(again.out.find("ran          dataset generator changed"), std::string::npos)
      << again.out;
  EXPECT_NE(sh(dir.path(), kCnclab + " reproduce e.yaml --quiet").out.find("reused"),
            std::string::npos);
}

TEST(GraphCli, RunWithoutUpstreamResultSaysHowToMakeIt) {
  TempDir dir;
  std::ofstream(dir / "up.yaml") << "include: " << kExperiment << "\nname: up\n";
  std::ofstream(dir / "down.yaml") << "include: up.yaml\nname: down\ninit_from: {experiment: "
                                      "up.yaml}\n";
  const Result r = sh(dir.path(), kCnclab + " run down.yaml --quiet");
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("has no result"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("cnclab reproduce"), std::string::npos) << r.err;
  std::ofstream(dir / "missing.yaml") << "include: up.yaml\nname: m\nneeds: [nope.yaml]\n";
  expect_usage_error(sh(dir.path(), kCnclab + " validate missing.yaml"), "no experiment file");
}

}  // namespace
}  // namespace cnclab
