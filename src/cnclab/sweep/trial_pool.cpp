#include "cnclab/sweep/trial_pool.hpp"

#include <sched.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <thread>

#include "cnclab/core/error.hpp"
#include "cnclab/io/atomic_file.hpp"

namespace cnclab {
namespace {

constexpr int kExitResult = 0;    // result written (status complete)
constexpr int kExitFailed = 1;    // result written (status failed: diverged)
constexpr int kExitError = 3;     // no result; error note written
constexpr int kExitOrphaned = 4;  // parent gone before the trial started
constexpr int kExitConfig = 5;    // no result; ConfigError, its text in the error note

void write_note(const std::filesystem::path& path, const std::string& text) {
  AtomicOutput out(path);
  {
    std::ofstream f(out.temp_path(), std::ios::binary);
    f << text << "\n";
  }
  out.commit();
}

[[noreturn]] void run_child(const TrialJob& job, const PoolOptions& options, pid_t parent,
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
    RunOptions run = options.run;
    run.result_file = job.result_file;
    if (!options.trial_output) {
      run.log = nullptr;
      run.progress = ProgressMode::quiet;
    }
    if (job.task) {
      job.task();
      code = kExitResult;
    } else {
      code = run_experiment(*job.experiment, run).ok ? kExitResult : kExitFailed;
    }
  } catch (const std::exception& e) {
    if (dynamic_cast<const ConfigError*>(&e)) code = kExitConfig;
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

std::size_t available_cores() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0) {
    return static_cast<std::size_t>(std::max(1, CPU_COUNT(&set)));
  }
  return std::max<std::size_t>(1, std::thread::hardware_concurrency());
}

int run_trial_pool(const std::vector<TrialJob>& jobs, const PoolOptions& options,
                   const std::function<void(std::size_t, const TrialExit&)>& on_done) {
  std::size_t next = 0;
  const auto next_ready = [&]() -> std::optional<TrialJob> {
    if (next == jobs.size()) return std::nullopt;
    TrialJob job = jobs[next];
    job.index = next++;
    return job;
  };
  return run_trial_pool(next_ready, options, on_done);
}

int run_trial_pool(const std::function<std::optional<TrialJob>()>& next_ready,
                   const PoolOptions& options,
                   const std::function<void(std::size_t, const TrialExit&)>& on_done) {
  if (options.jobs < 1) throw ConfigError("--jobs 0: must be at least 1");
  sigset_t watched;
  sigemptyset(&watched);
  sigaddset(&watched, SIGCHLD);
  sigaddset(&watched, SIGINT);
  sigaddset(&watched, SIGTERM);
  sigaddset(&watched, SIGUSR1);
  const BlockedSignals blocked(watched);
  const pid_t self = ::getpid();

  using Clock = std::chrono::steady_clock;
  struct Running {
    TrialJob job;
    Clock::time_point start;
    bool timed_out = false;
  };
  std::map<pid_t, Running> running;
  std::optional<TrialJob> pending;  // taken from next_ready, not yet started (fork failed)
  int stop_signal = 0;
  int drain_signal = 0;  // SIGUSR1 received: start nothing, let the running trials end
  const auto reap = [&](pid_t pid, int status) {
    const auto it = running.find(pid);
    if (it == running.end()) return;  // not a trial (e.g. a read probe)
    const TrialJob job = it->second.job;
    const bool timed_out = it->second.timed_out;
    running.erase(it);
    TrialExit exit;
    if (timed_out) {
      exit.kind = TrialExit::Kind::error;
      exit.timeout = true;
      std::ostringstream m;
      m << kTimeoutNote << " killed after running longer than " << options.trial_timeout_seconds
        << " s (--trial-timeout)";
      exit.message = m.str();
      try {
        write_note(job.error_file, exit.message);
      } catch (const std::exception&) {
      }
    } else if (WIFEXITED(status)) {
      const int code = WEXITSTATUS(status);
      exit.kind = code == kExitResult || code == kExitFailed ? TrialExit::Kind::result
                                                             : TrialExit::Kind::error;
      if (code == kExitOrphaned) exit.kind = TrialExit::Kind::interrupted;
      if (exit.kind == TrialExit::Kind::error) exit.message = "exit code " + std::to_string(code);
      exit.config_error = code == kExitConfig;
    } else {
      const int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
      if (stop_signal != 0) {
        exit.kind = TrialExit::Kind::interrupted;
      } else {
        exit.kind = TrialExit::Kind::error;
        exit.message = "trial process killed by " + signal_text(sig);
        try {
          write_note(job.error_file, exit.message);
        } catch (const std::exception&) {
        }
      }
    }
    on_done(job.index, exit);
  };

  for (;;) {
    while (stop_signal == 0 && drain_signal == 0 && running.size() < options.jobs) {
      if (!pending) pending = next_ready();
      if (!pending) break;
      std::cout.flush();
      std::cerr.flush();
      const pid_t pid = ::fork();
      if (pid < 0) {
        if (running.empty())
          throw Error(std::string("cannot fork a trial: ") + std::strerror(errno));
        break;  // retry when a slot frees
      }
      if (pid == 0) run_child(*pending, options, self, blocked.original());
      running.emplace(pid, Running{std::move(*pending), Clock::now()});
      pending.reset();
    }
    // Reap everything that ended (on_done may make more jobs ready), then
    // wait for the next event.
    bool reaped = false;
    for (;;) {
      int status = 0;
      const pid_t pid = ::waitpid(-1, &status, WNOHANG);
      if (pid <= 0) break;
      reap(pid, status);
      reaped = true;
    }
    if (running.empty()) {
      if (stop_signal == 0 && drain_signal == 0 && (reaped || pending)) continue;
      break;
    }
    const timespec tick{1, 0};  // also a safety net against a missed SIGCHLD
    siginfo_t info;
    const int sig = ::sigtimedwait(&watched, &info, &tick);
    if (options.on_tick) options.on_tick();
    if (sig == SIGUSR1) drain_signal = sig;
    if ((sig == SIGINT || sig == SIGTERM) && stop_signal == 0) {
      stop_signal = sig;
      for (const auto& [pid, trial] : running) ::kill(pid, SIGTERM);
    }
    if (options.trial_timeout_seconds > 0 && stop_signal == 0) {
      const auto now = Clock::now();
      for (auto& [pid, trial] : running) {
        const double seconds = std::chrono::duration<double>(now - trial.start).count();
        if (trial.job.timed && !trial.timed_out && seconds > options.trial_timeout_seconds) {
          trial.timed_out = true;
          ::kill(pid, SIGKILL);
        }
      }
    }
  }
  // Drop pending SIGCHLDs of our children before the mask is restored.
  const timespec zero{0, 0};
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  while (::sigtimedwait(&chld, nullptr, &zero) > 0) {
  }
  return stop_signal != 0 ? stop_signal : drain_signal;
}

}  // namespace cnclab
