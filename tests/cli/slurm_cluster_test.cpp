// `cnclab sweep --slurm` on a real single-node Slurm (scripts/slurm_local:
// Debian's slurm-wlm and munge, started here and always stopped): submit a
// sweep as a job array of 2 concurrent tasks, cancel one task mid-run, send
// another the pre-emption warning (it finishes its running trial and
// requeues itself), resubmit, wait, and compare the merged summary with a
// local `--jobs 2` run trial for trial (bit-identical metrics and network
// parameters), with no trial run twice; then `reproduce --slurm` of a small
// graph with a sweep job against a local reproduce. Independent reference: the local run
// shares no code with the Slurm path beyond the trial itself.
//
// Skipped (not failed) when the daemons cannot run here: not root, or
// slurm-wlm / munge not installed.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <thread>

#include "cnclab/experiment/result_file.hpp"
#include "cnclab/sweep/slurm_submission.hpp"
#include "cnclab/sweep/sweep_summary.hpp"
#include "common/process.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::run_shell;
using testing::ShellResult;
using testing::slurp;
using testing::TempDir;

const std::string kCnclab = CNCLAB_BINARY_DIR "/cnclab";
const std::string kSlurmLocal = CNCLAB_SOURCE_DIR "/scripts/slurm_local";
const std::string kExperiment = CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_mlp.yaml";
// True when a TCP socket can bind `port` on every address now.
bool port_free(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_in addr{};
  addr.sin_family = AF_INET;
  addr.sin_addr.s_addr = htonl(INADDR_ANY);
  addr.sin_port = htons(static_cast<std::uint16_t>(port));
  const bool ok = ::bind(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) == 0;
  ::close(fd);
  return ok;
}

// A port pair of its own (slurmctld PORT, slurmd PORT+1), free when the test
// starts: neither a developer's `scripts/slurm_local` on the default 6817
// nor daemons a killed earlier run left behind collide with the cluster.
int free_port_pair() {
  for (int port = 16817; port < 16817 + 200; port += 2) {
    if (port_free(port) && port_free(port + 1)) return port;
  }
  return 16817;  // none free: the start fails and says why
}
constexpr auto kWaitLimit = std::chrono::seconds(120);

// 6 trials (3 keep probabilities x 2 learning rates) of about 3 s each on an idle
// core (20000 epochs): long enough that a task is still mid-trial when the
// test cancels or warns it, on a loaded machine or not.
std::string sweep_words() {
  return kExperiment +
         " trainer.epochs=20000 dataset.options.samples=300 model.hidden=[16,8] "
         "model.dropout.keep_probability=0.8,0.9,1.0 trainer.learning_rate=1e-3,1e-2 "
         "--data-dir data";
}

// The cluster of scripts/slurm_local under `state`, stopped on destruction
// (also when an assertion ends the test early), and by a watchdog when this
// process ends without destructors (start_watchdog).
class LocalCluster {
 public:
  explicit LocalCluster(fs::path state) : state_(std::move(state)), port_(free_port_pair()) {}
  ~LocalCluster() {
    if (started_) run_shell(state_.parent_path(), env() + kSlurmLocal + " stop");
    std::error_code ignored;
    fs::remove_all(state_, ignored);
    if (watchdog_fd_ >= 0) ::close(watchdog_fd_);  // the watchdog's stop finds nothing left
  }
  LocalCluster(const LocalCluster&) = delete;
  LocalCluster& operator=(const LocalCluster&) = delete;

  ShellResult start() {
    start_watchdog();
    started_ = true;  // stop even a half-started cluster
    return run_shell(state_.parent_path(), env() + kSlurmLocal + " start");
  }
  // Prefix of a shell command that talks to this cluster.
  std::string env() const {
    return "CNCLAB_SLURM_DIR='" + state_.string() + "' CNCLAB_SLURM_PORT=" + std::to_string(port_) +
           " SLURM_CONF='" + (state_ / "etc/slurm.conf").string() + "' ";
  }

 private:
  // ctest ends a test past its TIMEOUT with SIGKILL, and its child processes
  // with it: no destructor runs, and the daemons (detached from us) would
  // keep running. So a watchdog outside our process tree (forked twice, a
  // session of its own, stdio on /dev/null so that ctest's output pipes
  // close) blocks reading a pipe whose write end only this process holds
  // (O_CLOEXEC: the shells and daemons we start do not inherit it). However
  // this process ends, the read returns and the watchdog stops the cluster.
  // Chosen over a FIXTURES_CLEANUP test: that needs a fixed state directory
  // and runs only under ctest, not when the binary is run or killed by hand;
  // and over a deadline inside the test: it needs no copy of ctest's TIMEOUT.
  void start_watchdog() {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return;
    const std::string stop = env() + kSlurmLocal + " stop; rm -rf '" + state_.string() + "'";
    const pid_t child = ::fork();
    if (child == 0) {  // async-signal-safe calls only until exec
      ::setsid();
      if (::fork() != 0) ::_exit(0);
      const int null = ::open("/dev/null", O_RDWR);
      for (int fd = 0; fd < 3; ++fd) ::dup2(null, fd);
      for (int fd = 3; fd < 1024; ++fd) {
        if (fd != fds[0]) ::close(fd);
      }
      char byte = 0;
      while (::read(fds[0], &byte, 1) < 0 && errno == EINTR) {
      }
      ::execl("/bin/bash", "bash", "-c", stop.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    ::close(fds[0]);
    if (child > 0) {
      ::waitpid(child, nullptr, 0);
      watchdog_fd_ = fds[1];
    } else {
      ::close(fds[1]);
    }
  }

  fs::path state_;
  int port_;  // slurmctld; slurmd listens on port_ + 1
  bool started_ = false;
  int watchdog_fd_ = -1;  // the pipe's write end: closed, the watchdog stops the cluster
};

std::string why_not_runnable() {
  if (::geteuid() != 0) return "not root (slurmd and munged run as root here)";
  for (const char* tool : {"/usr/sbin/munged", "/usr/sbin/slurmctld", "/usr/sbin/slurmd",
                           "/usr/bin/sbatch", "/usr/bin/squeue"}) {
    if (!fs::exists(tool)) return std::string(tool) + " missing (slurm-wlm, munge)";
  }
  return "";
}

// "<array>_<task>" -> state of the caller's array tasks.
std::map<std::string, std::string> task_states(const fs::path& dir, const LocalCluster& c) {
  const ShellResult r = run_shell(dir, c.env() + "squeue -h -r -t all -o '%F_%K %T'");
  std::map<std::string, std::string> states;
  std::istringstream in(r.out);
  std::string task, state;
  while (in >> task >> state) states[task] = state;
  return states;
}

bool queue_empty(const fs::path& dir, const LocalCluster& c) {
  return run_shell(dir, c.env() + "squeue -h -o %i").out.empty();
}

// Waits until `done()` or the limit; false on timeout.
template <class F>
bool wait_for(F done) {
  const auto end = std::chrono::steady_clock::now() + kWaitLimit;
  while (std::chrono::steady_clock::now() < end) {
    if (done()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
  }
  return false;
}

// Trial ids with a "[k/n] <id> ..." finished line in any task log: how
// often each trial ran to its end (a result written).
std::map<std::string, int> finished_runs(const fs::path& sweep) {
  std::map<std::string, int> runs;
  const std::regex line(R"(^\[\d+/\d+\] ([0-9a-f]{16}) )");
  for (const auto& sub : fs::directory_iterator(sweep / "slurm")) {
    for (const auto& log : fs::directory_iterator(sub.path() / "logs")) {
      std::istringstream in(slurp(log.path()));
      std::string text;
      std::smatch m;
      while (std::getline(in, text)) {
        // A trial killed with its task ends as "error: ..." (it runs again).
        if (std::regex_search(text, m, line) && text.find(": error:") == std::string::npos) {
          ++runs[m[1].str()];
        }
      }
    }
  }
  return runs;
}

// The result files under `folder` (results/<name>/) by file name.
std::map<std::string, fs::path> results_in(const fs::path& folder) {
  std::map<std::string, fs::path> files;
  for (const auto& e : fs::directory_iterator(folder)) {
    if (e.path().extension() == ".h5") files[e.path().filename().string()] = e.path();
  }
  return files;
}

// `reproduce --slurm` of a graph (b needs a) and a `kind: sweep` of a: the
// jobs run in dependency order and give the local reproduce's results bit
// for bit; run again, everything is reused and nothing submitted.
void reproduce_graph_on(const LocalCluster& cluster, const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream(dir / "a.yaml") << "include: " << kExperiment
                                << "\nname: a\ntrainer: {epochs: 3}\n"
                                   "dataset: {options: {samples: 200}}\n";
  std::ofstream(dir / "b.yaml") << "include: a.yaml\nname: b\ninit_from: {experiment: a.yaml}\n";
  std::ofstream(dir / "s.yaml") << "kind: sweep\nname: s\nexperiment: a.yaml\nsweep:\n"
                                   "  parameters: {trainer.learning_rate: [0.001, 0.01]}\n";
  const std::string files = " a.yaml b.yaml s.yaml --data-dir data";
  const ShellResult local =
      run_shell(dir, kCnclab + " reproduce" + files + " --out local --jobs 2 --quiet");
  ASSERT_EQ(local.code, 0) << local.out << local.err;
  const std::string submit =
      cluster.env() + kCnclab + " reproduce" + files + " --out slurm --slurm";
  const ShellResult first = run_shell(dir, submit);
  ASSERT_EQ(first.code, 0) << first.out << first.err;
  ASSERT_TRUE(wait_for([&] { return queue_empty(dir, cluster); })) << "jobs still queued";
  // a's folder also holds the sweep's trials (results of a's file).
  for (const char* name : {"a", "b"}) {
    const auto local_files = results_in(dir / "local" / name);
    const auto slurm_files = results_in(dir / "slurm" / name);
    ASSERT_EQ(local_files.size(), slurm_files.size()) << name;
    for (const auto& [file, path] : local_files) {
      ASSERT_TRUE(slurm_files.count(file)) << file;
      const RunRecord l = read_result(path);
      const RunRecord r = read_result(slurm_files.at(file));
      EXPECT_EQ(l.metrics, r.metrics) << file;
      EXPECT_EQ(l.parameters, r.parameters) << file;
      EXPECT_EQ(l.upstream.size(), r.upstream.size()) << file;
    }
  }
  // The sweep job's final job selected the same trial as the local run.
  const auto selected = [](const std::string& text) {
    const auto at = text.find("  trial: ");
    return at == std::string::npos ? std::string("none") : text.substr(at, 27);
  };
  EXPECT_EQ(selected(slurp(dir / "slurm/s/selection.yaml")),
            selected(slurp(dir / "local/s/selection.yaml")));
  EXPECT_NE(selected(slurp(dir / "local/s/selection.yaml")), "none");
  const ShellResult again = run_shell(dir, submit);
  ASSERT_EQ(again.code, 0) << again.out << again.err;
  EXPECT_EQ(again.out.find("submitted"), std::string::npos) << again.out;
  EXPECT_NE(again.out.find("s" + std::string(28, ' ') + "reused"), std::string::npos) << again.out;
}

TEST(SlurmCluster, ArraySweepSurvivesCancelAndPreemptionAndMatchesLocalRun) {
  const std::string why = why_not_runnable();
  if (!why.empty()) GTEST_SKIP() << "no local Slurm: " << why;
  TempDir tmp;
  const fs::path dir = tmp.path();
  // Short: munged's socket path lives in it (at most 108 bytes).
  const fs::path state = fs::temp_directory_path() / ("cnclab-slurm-" + std::to_string(::getpid()));
  LocalCluster cluster(state);
  const ShellResult started = cluster.start();
  ASSERT_EQ(started.code, 0) << "scripts/slurm_local start failed (daemons could not start):\n"
                             << started.out << started.err;

  // The reference: the same sweep run locally with 2 jobs.
  const ShellResult local = run_shell(
      dir, kCnclab + " sweep " + sweep_words() + " --jobs 2 --quiet --out local --dir local/sw");
  ASSERT_EQ(local.code, 0) << local.out << local.err;

  // Submission: 3 array tasks of 2 trials, 2 at once.
  const std::string submit = cluster.env() + kCnclab + " sweep " + sweep_words() +
                             " --out slurm --dir slurm/sw --slurm --tasks 3 --max-concurrent 2";
  const ShellResult first = run_shell(dir, submit);
  ASSERT_EQ(first.code, 0) << first.out << first.err;
  EXPECT_NE(first.out.find("6 of 6 trials to submit"), std::string::npos) << first.out;
  const auto subs = read_submissions(dir / "slurm/sw");
  ASSERT_EQ(subs.size(), 1u);
  const std::string array = subs[0].array_job;
  ASSERT_EQ(subs[0].tasks.size(), 3u);

  // Tasks 0 and 1 run (the throttle holds task 2 back): cancel task 0, warn task 1.
  ASSERT_TRUE(wait_for([&] {
    const auto s = task_states(dir, cluster);
    return s.count(array + "_0") && s.at(array + "_0") == "RUNNING" && s.count(array + "_1") &&
           s.at(array + "_1") == "RUNNING";
  })) << "the first two array tasks never ran together";
  std::this_thread::sleep_for(std::chrono::milliseconds(800));  // mid-trial
  ASSERT_EQ(run_shell(dir, cluster.env() + "scancel " + array + "_0").code, 0);
  ASSERT_EQ(run_shell(dir, cluster.env() + "scancel --signal=USR1 --batch " + array + "_1").code,
            0);
  ASSERT_TRUE(wait_for([&] {
    const auto s = task_states(dir, cluster);
    return s.count(array + "_0") && s.at(array + "_0") == "CANCELLED";
  }));

  // Resubmission while tasks 1 and 2 are still queued or running: only the
  // cancelled task's trials without a result go again.
  const ShellResult second = run_shell(dir, submit);
  ASSERT_EQ(second.code, 0) << second.out << second.err;
  const auto after = read_submissions(dir / "slurm/sw");
  ASSERT_EQ(after.size(), 2u) << second.out;
  const std::set<std::string> task0(subs[0].tasks[0].begin(), subs[0].tasks[0].end());
  for (const auto& ids : after[1].tasks) {
    for (const auto& id : ids)
      EXPECT_TRUE(task0.count(id)) << id << " was not the cancelled task's";
  }

  ASSERT_TRUE(wait_for([&] { return queue_empty(dir, cluster); })) << "jobs still queued";
  const ShellResult status = run_shell(dir, cluster.env() + kCnclab + " status slurm/sw");
  EXPECT_NE(status.out.find("complete 6, failed 0, running 0, pending 0, not queued 0"),
            std::string::npos)
      << status.out << status.err;
  // Task 1 was warned, requeued and ran again.
  EXPECT_NE(slurp(dir / "slurm/sw/slurm/submit-001/logs/task-1.out").find("requeueing"),
            std::string::npos);

  // The merge jobs' summary equals the local run's, trial for trial.
  ASSERT_TRUE(fs::exists(dir / "slurm/sw/summary.h5"));
  const StoredSummary a = read_summary(dir / "local/sw/summary.h5");
  const StoredSummary b = read_summary(dir / "slurm/sw/summary.h5");
  ASSERT_EQ(a.plan.hash(), b.plan.hash());
  ASSERT_EQ(a.outcomes.size(), b.outcomes.size());
  for (std::size_t i = 0; i < a.outcomes.size(); ++i) {
    EXPECT_EQ(to_string(b.outcomes[i].status), "complete");
    EXPECT_EQ(a.outcomes[i].metrics, b.outcomes[i].metrics) << a.plan.trials[i].id;
    const std::string file = "trials/" + a.plan.trials[i].id + ".h5";
    const RunRecord ra = read_result(dir / "local/sw" / file);
    const RunRecord rb = read_result(dir / "slurm/sw" / file);
    EXPECT_EQ(ra.parameters, rb.parameters) << file;
    EXPECT_EQ(ra.test_predictions, rb.test_predictions) << file;
  }
  EXPECT_EQ(a.best_trial, b.best_trial);
  // No trial ran to its end twice (cancelled runs never reached the end).
  for (const auto& [id, n] : finished_runs(dir / "slurm/sw")) EXPECT_EQ(n, 1) << id;
  EXPECT_EQ(finished_runs(dir / "slurm/sw").size(), 6u);

  reproduce_graph_on(cluster, dir / "graph");
}

// One study over a job array (model_search.hpp): a TPE sweep submitted as 2
// worker tasks that run at once against one journal; one task's worker is
// killed with SIGKILL mid-trial; the array's merge job and a resubmission
// (one worker task: the study lacks one trial) leave the study complete.
// Checked by Optuna's own reading of the journal: no trial number twice,
// exactly the requested count complete, none left running, the killed
// worker's trial failed; then nothing is left to submit.
struct StudyTrial {
  long number = 0;
  std::string state;  // COMPLETE, PRUNED, RUNNING, FAIL
  long pid = 0;       // the worker holding (or that held) it
};

std::vector<StudyTrial> study_trials(const fs::path& journal) {
  const ShellResult r = run_shell(
      journal.parent_path(),
      "/usr/bin/python3 -W ignore -c \"import sys, optuna\n"
      "from optuna.storages import JournalStorage, JournalFileStorage\n"
      "optuna.logging.set_verbosity(optuna.logging.ERROR)\n"
      "s = optuna.load_study(study_name='cnclab', storage=JournalStorage(JournalFileStorage("
      "sys.argv[1])))\n"
      "for t in s.trials: print(t.number, t.state.name, t.user_attrs.get('cnclab_pid', 0))\" '" +
          journal.string() + "'");
  std::vector<StudyTrial> trials;
  std::istringstream in(r.out);
  StudyTrial t;
  while (in >> t.number >> t.state >> t.pid) trials.push_back(t);
  return trials;
}

TEST(SlurmCluster, StudyOfTwoArrayTasksSurvivesKillAndResubmit) {
  const std::string why = why_not_runnable();
  if (!why.empty()) GTEST_SKIP() << "no local Slurm: " << why;
  if (run_shell(".", "/usr/bin/python3 -c 'import optuna'").code != 0)
    GTEST_SKIP() << "no python3-optuna for /usr/bin/python3";
  TempDir tmp;
  const fs::path dir = tmp.path();
  const fs::path state =
      fs::temp_directory_path() / ("cnclab-slurm-study-" + std::to_string(::getpid()));
  LocalCluster cluster(state);
  const ShellResult started = cluster.start();
  ASSERT_EQ(started.code, 0) << started.out << started.err;

  // 6 trials of about 3 s on an idle core (20000 epochs, as above).
  const std::string submit =
      cluster.env() + kCnclab + " sweep " + kExperiment +
      " trainer.epochs=20000 dataset.options.samples=300 model.hidden=[16,8]"
      " 'trainer.learning_rate=log_uniform(1e-3,1e-1)' 'model.dropout.keep_probability="
      "uniform(0.8,1.0)' --method tpe --trials 6 --sweep-seed 5 --data-dir data --out slurm"
      " --dir slurm/study --slurm --tasks 2";
  const ShellResult first = run_shell(dir, submit);
  ASSERT_EQ(first.code, 0) << first.out << first.err;
  EXPECT_NE(first.out.find("2 worker task(s) to submit"), std::string::npos) << first.out;
  const auto subs = read_submissions(dir / "slurm/study");
  ASSERT_EQ(subs.size(), 1u);
  const std::string array = subs[0].array_job;

  // Both tasks run at once, each a worker of the study: kill one worker
  // (SIGKILL, its running trial left RUNNING in the journal).
  const fs::path journal = dir / "slurm/study/study.journal";
  long victim = 0;
  ASSERT_TRUE(wait_for([&] {
    const auto s = task_states(dir, cluster);
    if (!(s.count(array + "_0") && s.at(array + "_0") == "RUNNING" && s.count(array + "_1") &&
          s.at(array + "_1") == "RUNNING") ||
        !fs::exists(journal))
      return false;
    std::set<long> holders;
    for (const auto& t : study_trials(journal))
      if (t.state == "RUNNING") holders.insert(t.pid);
    if (holders.size() < 2) return false;  // both workers mid-trial
    victim = *holders.begin();
    return true;
  })) << "the two worker tasks never ran trials together";
  ASSERT_GT(victim, 0);
  ASSERT_EQ(::kill(static_cast<pid_t>(victim), SIGKILL), 0);
  ASSERT_TRUE(wait_for([&] { return queue_empty(dir, cluster); })) << "jobs still queued";
  std::size_t finished = 0;
  for (const auto& t : study_trials(journal)) finished += t.state == "COMPLETE";
  EXPECT_EQ(finished, 5u) << "the surviving worker stops at the count, the killed trial held";

  // Resubmission: one worker task for the missing trial.
  const ShellResult second = run_shell(dir, submit);
  ASSERT_EQ(second.code, 0) << second.out << second.err;
  EXPECT_NE(second.out.find("1 worker task(s) to submit"), std::string::npos) << second.out;
  ASSERT_TRUE(wait_for([&] { return queue_empty(dir, cluster); })) << "jobs still queued";

  const auto trials = study_trials(journal);
  std::set<long> numbers;
  std::size_t complete = 0, running = 0, killed = 0;
  for (const auto& t : trials) {
    EXPECT_TRUE(numbers.insert(t.number).second) << "trial number " << t.number << " twice";
    complete += t.state == "COMPLETE";
    running += t.state == "RUNNING";
    killed += t.state == "FAIL" && t.pid == victim;
  }
  EXPECT_EQ(complete, 6u);
  EXPECT_EQ(running, 0u);
  EXPECT_GE(killed, 1u) << "the killed worker's trial is failed";
  // The merge job's summary lists the study's 6 trials, all complete.
  const StoredSummary summary = read_summary(dir / "slurm/study/summary.h5");
  std::size_t ranked = 0;
  for (const auto& o : summary.outcomes) ranked += o.status == TrialOutcome::Status::complete;
  EXPECT_EQ(ranked, 6u);
  const ShellResult third = run_shell(dir, submit);
  ASSERT_EQ(third.code, 0) << third.out << third.err;
  EXPECT_NE(third.out.find("nothing to submit"), std::string::npos) << third.out;
}

}  // namespace
}  // namespace cnclab
