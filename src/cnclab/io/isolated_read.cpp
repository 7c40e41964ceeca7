#include "cnclab/io/isolated_read.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/core/resources.hpp"

// AddressSanitizer reserves terabytes of virtual memory: an address-space
// limit would break it, so sanitizer builds rely on its own allocator limits.
#if defined(__SANITIZE_ADDRESS__)
#define CNCLAB_HAS_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define CNCLAB_HAS_ASAN 1
#endif
#endif

// Present only in sanitizer runtimes (weak: null otherwise). libFuzzer sets
// it to record the current input as a crash when a sanitizer reports.
extern "C" void __sanitizer_set_death_callback(void (*callback)(void)) __attribute__((weak));

namespace cnclab {
namespace {

constexpr int kExitIoError = 3;
constexpr int kExitOtherError = 4;

// A forked child inherits the parent's signal handlers. A fuzzer's (libFuzzer
// records the current input as a crash finding, then exits) or a crash
// reporter's would run on a libhdf5 crash in the child; a handler for
// SIGALRM, or SIG_IGN, would defeat the time limit. The child's faults take
// the default action instead, so the parent sees only a child killed by a
// signal, which it reports as an IoError. SIGINT and SIGTERM keep the
// parent's handling: an interrupted read is not a corrupt file.
void restore_default_fault_handling() {
  constexpr int kFaults[] = {SIGSEGV, SIGBUS, SIGABRT, SIGFPE, SIGILL, SIGTRAP, SIGSYS, SIGALRM};
  struct sigaction action {};
  action.sa_handler = SIG_DFL;
  sigemptyset(&action.sa_mask);
  sigset_t faults;
  sigemptyset(&faults);
  for (const int sig : kFaults) {
    ::sigaction(sig, &action, nullptr);
    sigaddset(&faults, sig);
  }
  ::sigprocmask(SIG_UNBLOCK, &faults, nullptr);
  // The handlers' alternate stack (a sanitizer's or a fuzzer's) is theirs.
  stack_t no_stack{};
  no_stack.ss_flags = SS_DISABLE;
  ::sigaltstack(&no_stack, nullptr);
  // A sanitizer report in the child then just exits non-zero.
  if (__sanitizer_set_death_callback != nullptr) __sanitizer_set_death_callback(nullptr);
}

[[noreturn]] void child(int fd, const std::function<void()>& read, double seconds) {
  // Library diagnostics and sanitizer reports of the probe are not ours to print.
  const int devnull = ::open("/dev/null", O_WRONLY);
  if (devnull >= 0) ::dup2(devnull, STDERR_FILENO);
  // SIGALRM after `seconds` of wall time (setitimer: fractions of a second too).
  itimerval timer{};
  timer.it_value.tv_sec = static_cast<time_t>(seconds);
  timer.it_value.tv_usec = static_cast<suseconds_t>((seconds - std::floor(seconds)) * 1e6);
  ::setitimer(ITIMER_REAL, &timer, nullptr);
#ifndef CNCLAB_HAS_ASAN
  const rlim_t limit = memory_budget_bytes() / 2;
  const rlimit as{limit, limit};
  ::setrlimit(RLIMIT_AS, &as);
#endif
  std::string message;
  int code = 0;
  try {
    read();
  } catch (const IoError& e) {
    message = e.what();
    code = kExitIoError;
  } catch (const std::exception& e) {
    message = e.what();
    code = kExitOtherError;
  } catch (...) {
    code = kExitOtherError;
  }
  for (std::size_t done = 0; done < message.size();) {
    const ssize_t n = ::write(fd, message.data() + done, message.size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::_exit(code);  // no exit handlers, no leak check: the parent decides
}

}  // namespace

void probe_in_child(const std::filesystem::path& file, const std::function<void()>& read,
                    double timeout_seconds) {
  timeout_seconds = std::max(timeout_seconds, 1e-6);  // a zero timer would set no limit
  int fds[2];
  if (::pipe(fds) != 0)
    throw IoError(file.string() + ": cannot create pipe: " + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    throw IoError(file.string() + ": cannot fork to read safely: " + std::strerror(errno));
  }
  if (pid == 0) {
    restore_default_fault_handling();
    ::close(fds[0]);
    child(fds[1], read, timeout_seconds);
  }
  ::close(fds[1]);
  std::string message;
  char buffer[4096];
  for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    message.append(buffer, static_cast<std::size_t>(n));
  }
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFEXITED(status)) {
    switch (WEXITSTATUS(status)) {
      case 0:
        return;
      case kExitIoError:
        throw IoError(message);
      default:
        throw IoError(file.string() + ": unreadable: " + message);
    }
  }
  const int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  if (sig == SIGALRM) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", timeout_seconds);
    throw ProbeTimedOut(file.string() + ": corrupt HDF5 file: the HDF5 library did not finish " +
                        "reading it in " + seconds + " s");
  }
  throw IoError(file.string() +
                ": corrupt HDF5 file: the HDF5 library crashed reading it (signal " +
                std::to_string(sig) + ", " + ::strsignal(sig) + ")");
}

}  // namespace cnclab
