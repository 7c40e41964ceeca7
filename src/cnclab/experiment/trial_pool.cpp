#include "cnclab/experiment/trial_pool.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>

#include "cnclab/core/error.hpp"
#include "cnclab/io/atomic_file.hpp"

namespace cnclab {
namespace {

constexpr int kExitResult = 0;    // result written (status complete)
constexpr int kExitFailed = 1;    // result written (status failed: diverged)
constexpr int kExitError = 3;     // no result; error note written
constexpr int kExitOrphaned = 4;  // parent gone before the trial started

void write_note(const std::filesystem::path& path, const std::string& text) {
  AtomicOutput out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << text << "\n";
  }
  out.commit();
}

[[noreturn]] void run_child(const TrialJob& job, const RunOptions& base, pid_t parent,
                            const sigset_t& original_mask) {
  // The pool's blocked signals are the parent's business; a trial dies on
  // SIGINT/SIGTERM like any program, and with its parent.
  ::signal(SIGINT, SIG_DFL);
  ::signal(SIGTERM, SIG_DFL);
  ::sigprocmask(SIG_SETMASK, &original_mask, nullptr);
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  if (::getppid() != parent) ::_exit(kExitOrphaned);
  int code = kExitError;
  try {
    RunOptions run = base;
    run.result_file = job.result_file;
    run.log = nullptr;
    run.progress = ProgressMode::quiet;
    code = run_experiment(*job.experiment, run).ok ? kExitResult : kExitFailed;
  } catch (const std::exception& e) {
    try {
      write_note(job.error_file, e.what());
    } catch (const std::exception&) {
      // Nothing more to do: the parent records the exit code.
    }
  }
  ::_exit(code);  // no exit handlers: the parent owns stdio buffers and HDF5 state
}

// Blocks `signals` for its lifetime (also when an exception leaves the pool).
class BlockedSignals {
 public:
  explicit BlockedSignals(const sigset_t& signals) {
    ::sigprocmask(SIG_BLOCK, &signals, &original_);
  }
  ~BlockedSignals() { ::sigprocmask(SIG_SETMASK, &original_, nullptr); }
  BlockedSignals(const BlockedSignals&) = delete;
  BlockedSignals& operator=(const BlockedSignals&) = delete;
  const sigset_t& original() const { return original_; }

 private:
  sigset_t original_;
};

std::string signal_text(int sig) {
  return "signal " + std::to_string(sig) + " (" + ::strsignal(sig) + ")";
}

}  // namespace

int run_trial_pool(const std::vector<TrialJob>& jobs, const PoolOptions& options,
                   const std::function<void(std::size_t, const TrialExit&)>& on_done) {
  if (options.jobs < 1) throw ConfigError("--jobs 0: must be at least 1");
  sigset_t watched;
  sigemptyset(&watched);
  sigaddset(&watched, SIGCHLD);
  sigaddset(&watched, SIGINT);
  sigaddset(&watched, SIGTERM);
  const BlockedSignals blocked(watched);
  const pid_t self = ::getpid();

  std::map<pid_t, std::size_t> running;
  std::size_t next = 0;
  int stop_signal = 0;
  const auto reap = [&](pid_t pid, int status) {
    const auto it = running.find(pid);
    if (it == running.end()) return;  // not a trial (e.g. a read probe)
    const std::size_t job = it->second;
    running.erase(it);
    TrialExit exit;
    if (WIFEXITED(status)) {
      const int code = WEXITSTATUS(status);
      exit.kind = code == kExitResult || code == kExitFailed ? TrialExit::Kind::result
                                                             : TrialExit::Kind::error;
      if (code == kExitOrphaned) exit.kind = TrialExit::Kind::interrupted;
      if (exit.kind == TrialExit::Kind::error) exit.message = "exit code " + std::to_string(code);
    } else {
      const int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
      if (stop_signal != 0) {
        exit.kind = TrialExit::Kind::interrupted;
      } else {
        exit.kind = TrialExit::Kind::error;
        exit.message = "trial process killed by " + signal_text(sig);
        try {
          write_note(jobs[job].error_file, exit.message);
        } catch (const std::exception&) {
        }
      }
    }
    on_done(job, exit);
  };

  while ((stop_signal == 0 && next < jobs.size()) || !running.empty()) {
    while (stop_signal == 0 && next < jobs.size() && running.size() < options.jobs) {
      std::cout.flush();
      std::cerr.flush();
      const pid_t pid = ::fork();
      if (pid < 0) {
        if (running.empty())
          throw Error(std::string("cannot fork a trial: ") + std::strerror(errno));
        break;  // retry when a slot frees
      }
      if (pid == 0) run_child(jobs[next], options.run, self, blocked.original());
      running[pid] = next++;
    }
    // Reap everything that ended, then wait for the next event.
    for (;;) {
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, WNOHANG);
      if (pid <= 0) break;
      reap(pid, status);
    }
    if (running.empty()) continue;
    const timespec tick{1, 0};  // also a safety net against a missed SIGCHLD
    siginfo_t info;
    const int sig = ::sigtimedwait(&watched, &info, &tick);
    if ((sig == SIGINT || sig == SIGTERM) && stop_signal == 0) {
      stop_signal = sig;
      for (const auto& [pid, job] : running) ::kill(pid, SIGTERM);
    }
  }
  // Drop pending SIGCHLDs of our children before the mask is restored.
  const timespec zero{0, 0};
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  while (::sigtimedwait(&chld, nullptr, &zero) > 0) {
  }
  return stop_signal;
}

}  // namespace cnclab
