// `cnclab sweep --slurm` and `cnclab status` without a cluster: the generated
// scripts (checked by bash -n), what a submission records, which trials a
// resubmission sends (fake sbatch/squeue on PATH report what a cluster would),
// the pre-emption path of the array script run by bash itself, and bad
// inputs. The real cluster: slurm_cluster_test.cpp.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <thread>

#include "cnclab/sweep/slurm_queue.hpp"
#include "cnclab/sweep/slurm_submission.hpp"
#include "cnclab/sweep/slurm_tools.hpp"
#include "common/fake_slurm.hpp"
#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::fake_slurm;
using testing::run_shell;
using testing::ShellResult;
using testing::slurp;
using testing::TempDir;
using testing::write_tool;

using testing::kSlurmTestCnclab;
using testing::kSlurmTestExperiment;

// 6 small trials.
std::string sweep_words(const std::string& epochs = "5") {
  return kSlurmTestExperiment + " trainer.epochs=" + epochs +
         " dataset.options.samples=200 model.hidden=[8] "
         "model.dropout.keep_probability=0.8,0.9,1.0 trainer.learning_rate=1e-3,1e-2 "
         "--data-dir data --out r --dir sw";
}

TEST(SlurmParse, SqueueAndSacctLines) {
  const auto q = parse_squeue_tasks("12|0|RUNNING\n12|1|PENDING\n13|N/A|PENDING\n");
  ASSERT_EQ(q.size(), 2u);
  EXPECT_EQ(q.at("12_0"), "RUNNING");
  EXPECT_EQ(q.at("12_1"), "PENDING");
  const auto a = parse_sacct_tasks("12_0|COMPLETED\n12_[2-5]|PENDING\n12_1|CANCELLED by 0\n");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(slurm_phase(a.at("12_1")), SlurmPhase::ended);
  EXPECT_EQ(slurm_phase("REQUEUED"), SlurmPhase::queued);
  EXPECT_EQ(slurm_phase("PREEMPTED"), SlurmPhase::queued);
  EXPECT_EQ(slurm_phase("COMPLETING"), SlurmPhase::running);
  EXPECT_EQ(slurm_phase("SOMETHING_NEW"), SlurmPhase::queued);  // never resubmitted on a guess
}

TEST(SlurmParse, TasksDealtRoundRobinAndShellQuoting) {
  const auto t = split_into_tasks({"a", "b", "c", "d", "e"}, 2);
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t[0], (std::vector<std::string>{"a", "c", "e"}));
  EXPECT_EQ(split_into_tasks({"a", "b"}, 0).size(), 2u);
  EXPECT_EQ(split_into_tasks({"a", "b"}, 5).size(), 2u);
  // Round trip through bash: the quoted word prints as itself.
  const std::string word = "it's a [1,2] $HOME `x`";
  TempDir tmp;
  const ShellResult r = run_shell(tmp.path(), "bash -c 'printf %s \"$1\"' _ " + shell_quote(word));
  EXPECT_EQ(r.out, word);
}

TEST(SlurmSweep, DryRunPrintsAValidArrayScriptAndWritesNothing) {
  TempDir tmp;
  const ShellResult r =
      run_shell(tmp.path(), kSlurmTestCnclab + " sweep " + sweep_words() +
                                " --slurm --dry-run --partition short --time 00:10:00 --mem 1G "
                                "--max-concurrent 2 --signal USR2@60 --cpus-per-task 2");
  ASSERT_EQ(r.code, 0) << r.err;
  for (const char* line :
       {"#SBATCH --array=0-5%2", "#SBATCH --partition=short", "#SBATCH --time=00:10:00",
        "#SBATCH --mem=1G", "#SBATCH --requeue", "#SBATCH --signal=B:USR2@60",
        "#SBATCH --cpus-per-task=2", "trap on_warning USR2", "6 of 6 trials to submit"}) {
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  }
  EXPECT_FALSE(fs::exists(tmp / "sw"));
  std::ofstream(tmp / "script.sh") << r.out;
  EXPECT_EQ(run_shell(tmp.path(), "bash -n script.sh").code, 0);
}

TEST(SlurmSweep, SubmitsRecordsAndResubmitsOnlyWhatIsNeitherDoneNorInFlight) {
  TempDir tmp;
  const std::string path = fake_slurm(tmp.path());
  const std::string submit =
      path + kSlurmTestCnclab + " sweep " + sweep_words() + " --slurm --tasks 3";
  const ShellResult first = run_shell(tmp.path(), submit);
  ASSERT_EQ(first.code, 0) << first.out << first.err;
  auto subs = read_submissions(tmp / "sw");
  ASSERT_EQ(subs.size(), 1u);
  EXPECT_EQ(subs[0].array_job, "100");
  EXPECT_EQ(subs[0].merge_job, "101");
  ASSERT_EQ(subs[0].tasks.size(), 3u);
  const std::string calls = slurp(tmp / "calls.txt");
  EXPECT_NE(calls.find("--dependency=afterany:100 "), std::string::npos) << calls;

  // Task 0 running, task 1 pending: only task 2's trials may go again.
  std::ofstream(tmp / "queue.txt") << "100|0|RUNNING\n100|1|PENDING\n100|2|FAILED\n";
  const ShellResult second = run_shell(tmp.path(), submit);
  ASSERT_EQ(second.code, 0) << second.out << second.err;
  EXPECT_NE(second.out.find("2 of 6 trials to submit (0 done, 4 queued or running)"),
            std::string::npos)
      << second.out;
  subs = read_submissions(tmp / "sw");
  ASSERT_EQ(subs.size(), 2u);
  EXPECT_EQ(subs[1].tasks.size(), 2u);  // --tasks 3, but 2 trials
  // The new merge job waits for both arrays and replaces the old merge job.
  const std::string calls2 = slurp(tmp / "calls.txt");
  EXPECT_NE(calls2.find("--dependency=afterany:102:100 "), std::string::npos) << calls2;
  EXPECT_NE(calls2.find("scancel --state=PENDING 101"), std::string::npos) << calls2;

  // Everything in flight: nothing to submit.
  std::ofstream(tmp / "queue.txt")
      << "100|0|RUNNING\n100|1|PENDING\n102|0|RUNNING\n102|1|RUNNING\n";
  const ShellResult third = run_shell(tmp.path(), submit);
  EXPECT_EQ(third.code, 0);
  EXPECT_NE(third.out.find("nothing to submit"), std::string::npos) << third.out;
  const ShellResult status = run_shell(tmp.path(), path + kSlurmTestCnclab + " status sw");
  EXPECT_EQ(status.code, 0) << status.err;
  EXPECT_NE(status.out.find("complete 0, failed 0, running 4, pending 2, not queued 0"),
            std::string::npos)
      << status.out;
  EXPECT_NE(status.out.find("accounting storage is disabled"), std::string::npos) << status.out;
}

TEST(SlurmSweep, BadInputsGiveClearErrorsAndLeaveNoSubmission) {
  TempDir tmp;
  // No sbatch on PATH.
  const ShellResult none = run_shell(
      tmp.path(), "PATH=/nonexistent " + kSlurmTestCnclab + " sweep " + sweep_words() + " --slurm");
  EXPECT_EQ(none.code, 1);
  EXPECT_NE(none.err.find("sbatch not found on PATH"), std::string::npos) << none.err;
  EXPECT_FALSE(fs::exists(tmp / "sw"));

  // sbatch rejects the array (an unknown partition).
  const std::string path = fake_slurm(tmp.path());
  write_tool(tmp / "bin", "sbatch",
             "echo 'sbatch: error: invalid partition specified: nope' >&2\nexit 1");
  const ShellResult rejected =
      run_shell(tmp.path(),
                path + kSlurmTestCnclab + " sweep " + sweep_words() + " --slurm --partition nope");
  EXPECT_EQ(rejected.code, 1);
  EXPECT_NE(rejected.err.find("sbatch rejected the job array (exit 1): sbatch: error: invalid "
                              "partition specified: nope"),
            std::string::npos)
      << rejected.err;
  EXPECT_TRUE(read_submissions(tmp / "sw").empty());
  EXPECT_TRUE(fs::is_empty(tmp / "sw/slurm"));

  // The folder holds another sweep (other epochs: other trials).
  const ShellResult other = run_shell(
      tmp.path(), path + kSlurmTestCnclab + " sweep " + sweep_words("6") + " --slurm --dry-run");
  EXPECT_EQ(other.code, 2);
  EXPECT_NE(other.err.find("holds another sweep"), std::string::npos) << other.err;

  // Options that make no sense.
  for (const char* bad : {" --slurm --signal TERM@60", " --slurm --jobs 2", " --slurm --shard 1/2",
                          " --partition short"}) {
    const ShellResult r =
        run_shell(tmp.path(), path + kSlurmTestCnclab + " sweep " + sweep_words() + bad);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.err;
  }
}

// The array script itself, run by bash as Slurm would (fake scontrol): on
// the warning signal the running trial finishes, no new one starts, and the
// task requeues itself; run again it does the rest.
TEST(SlurmSweep, WarningSignalDrainsTheTaskAndRequeuesIt) {
  TempDir tmp;
  const std::string path = fake_slurm(tmp.path());
  const ShellResult submitted = run_shell(
      tmp.path(), path + kSlurmTestCnclab + " sweep " + sweep_words("8000") + " --slurm --tasks 1");
  ASSERT_EQ(submitted.code, 0) << submitted.err;
  const fs::path script = tmp / "sw/slurm/submit-001/sweep.sbatch";
  // exec: the signal below reaches the script's own shell, as Slurm's B: does.
  const std::string run = "cd '" + tmp.path().string() + "' && exec env " + path +
                          "SLURM_ARRAY_TASK_ID=0 SLURM_JOB_ID=77 bash '" + script.string() + "'";
  const fs::path log = tmp / "task.log";
  const pid_t bash = testing::spawn_quiet(
      {"/bin/bash", "-c", "exec bash -c \"$0\" >'" + log.string() + "' 2>&1", run});
  ASSERT_GT(bash, 0);
  // Warn once the trials have started (the sweep's "running 6 with 1 job(s)"
  // line comes just before; each trial takes about a second).
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (slurp(log).find("running 6 with") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  ::kill(bash, SIGUSR1);
  EXPECT_EQ(testing::wait_exit(bash), 0);
  EXPECT_NE(slurp(tmp / "calls.txt").find("scontrol requeue 77"), std::string::npos);
  std::size_t results = 0;
  for (const auto& e : fs::directory_iterator(tmp / "sw/trials")) {
    results += e.path().extension() == ".h5" && e.path().filename().string()[0] != '.';
  }
  // The running trial finished (a drained pool never kills it); the rest waits.
  EXPECT_GE(results, 1u);
  EXPECT_LT(results, 6u);
  // Requeued, the task runs the others, and only those.
  const ShellResult again = run_shell(tmp.path(), run);
  EXPECT_EQ(again.code, 0) << again.out << again.err;
  EXPECT_NE(again.out.find("6 complete, 0 failed"), std::string::npos) << again.out;
  EXPECT_NE(again.err.find(std::to_string(results) + " already done, running " +
                           std::to_string(6 - results)),
            std::string::npos)
      << again.err;
}

// A model-based sweep: the array's tasks are workers of one study (no trial
// lists), as many as the study lacks trials, less the workers in flight.
TEST(SlurmSweep, StudySubmitsWorkerTasksForTheTrialsItLacks) {
  if (run_shell(".", "/usr/bin/python3 -c 'import optuna'").code != 0)
    GTEST_SKIP() << "no python3-optuna for /usr/bin/python3";
  TempDir tmp;
  const std::string path = fake_slurm(tmp.path());
  const std::string submit = path + kSlurmTestCnclab + " sweep " + kSlurmTestExperiment +
                             " trainer.epochs=5 dataset.options.samples=200 model.hidden=[8]"
                             " 'trainer.learning_rate=log_uniform(1e-3,1e-1)' --method tpe"
                             " --trials 4 --data-dir data --out r --dir sw --slurm --tasks 3";
  const ShellResult first = run_shell(tmp.path(), submit);
  ASSERT_EQ(first.code, 0) << first.out << first.err;
  EXPECT_NE(first.out.find("3 worker task(s) to submit (0 of 4 study trials complete or pruned, "
                           "0 worker task(s) queued or running)"),
            std::string::npos)
      << first.out;
  auto subs = read_submissions(tmp / "sw");
  ASSERT_EQ(subs.size(), 1u);
  ASSERT_EQ(subs[0].tasks.size(), 3u);
  const std::string script = slurp(tmp / "sw/slurm/submit-001/sweep.sbatch");
  EXPECT_EQ(script.find("--trial-ids"), std::string::npos) << script;
  EXPECT_NE(script.find("--trials 4 --method tpe"), std::string::npos) << script;
  EXPECT_EQ(run_shell(tmp.path(), "bash -n sw/slurm/submit-001/sweep.sbatch").code, 0);

  // Workers 0 and 1 in flight, 2 failed: 4 trials lacking, 2 more workers.
  std::ofstream(tmp / "queue.txt") << "100|0|RUNNING\n100|1|PENDING\n100|2|FAILED\n";
  const ShellResult second = run_shell(tmp.path(), submit);
  ASSERT_EQ(second.code, 0) << second.out << second.err;
  subs = read_submissions(tmp / "sw");
  ASSERT_EQ(subs.size(), 2u) << second.out;
  EXPECT_EQ(subs[1].tasks.size(), 2u) << second.out;
}

}  // namespace
}  // namespace cnclab
