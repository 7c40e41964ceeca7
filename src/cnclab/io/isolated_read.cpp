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
#include <optional>
#include <string>
#include <vector>

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

// The child's messages to the parent, one line each: "at I" before it reads
// file I; "error CODE" when that read threw, followed by the message up to the
// end of the pipe.
void write_all(int fd, const std::string& text) {
  for (std::size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n <= 0) return;
    done += static_cast<std::size_t>(n);
  }
}

// SIGALRM after `seconds` of wall time (setitimer: fractions of a second too).
void arm_timer(double seconds) {
  itimerval timer{};
  timer.it_value.tv_sec = static_cast<time_t>(seconds);
  timer.it_value.tv_usec = static_cast<suseconds_t>((seconds - std::floor(seconds)) * 1e6);
  ::setitimer(ITIMER_REAL, &timer, nullptr);
}

// Reads files begin, begin + 1, ... until one throws (exit with its code) or
// all are read (exit 0).
[[noreturn]] void child(int fd, std::size_t begin, std::size_t end,
                        const std::function<void(std::size_t)>& read, double seconds) {
  // Library diagnostics and sanitizer reports of the probe are not ours to print.
  const int devnull = ::open("/dev/null", O_WRONLY);
  if (devnull >= 0) ::dup2(devnull, STDERR_FILENO);
#ifndef CNCLAB_HAS_ASAN
  const rlim_t limit = memory_budget_bytes() / 2;
  const rlimit as{limit, limit};
  ::setrlimit(RLIMIT_AS, &as);
#endif
  for (std::size_t i = begin; i < end; ++i) {
    write_all(fd, "at " + std::to_string(i) + "\n");
    arm_timer(seconds);
    std::string message;
    int code = 0;
    try {
      read(i);
    } catch (const IoError& e) {
      message = e.what();
      code = kExitIoError;
    } catch (const std::exception& e) {
      message = e.what();
      code = kExitOtherError;
    } catch (...) {
      code = kExitOtherError;
    }
    if (code != 0) {
      write_all(fd, "error " + std::to_string(code) + "\n" + message);
      ::_exit(code);  // no exit handlers, no leak check: the parent decides
    }
  }
  ::_exit(0);
}

// What one child reported: the last file it started and, after "error", the
// message.
struct ChildReport {
  std::optional<std::size_t> at;
  std::string message;
};

ChildReport parse_report(const std::string& text) {
  ChildReport r;
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t eol = text.find('\n', pos);
    if (eol == std::string::npos) break;
    const std::string line = text.substr(pos, eol - pos);
    pos = eol + 1;
    if (line.rfind("at ", 0) == 0) {
      r.at = std::stoull(line.substr(3));
    } else if (line.rfind("error ", 0) == 0) {
      r.message = text.substr(pos);
      break;
    }
  }
  return r;
}

// The exception for `file` from a child's wait status and message.
std::exception_ptr failure(const std::filesystem::path& file, int status,
                           const std::string& message, double timeout_seconds) {
  if (WIFEXITED(status)) {
    if (WEXITSTATUS(status) == kExitIoError) return std::make_exception_ptr(IoError(message));
    return std::make_exception_ptr(IoError(file.string() + ": unreadable: " + message));
  }
  const int sig = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  if (sig == SIGALRM) {
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%g", timeout_seconds);
    return std::make_exception_ptr(
        ProbeTimedOut(file.string() + ": corrupt HDF5 file: the HDF5 library did not finish " +
                      "reading it in " + seconds + " s"));
  }
  return std::make_exception_ptr(
      IoError(file.string() + ": corrupt HDF5 file: the HDF5 library crashed reading it (signal " +
              std::to_string(sig) + ", " + ::strsignal(sig) + ")"));
}

}  // namespace

std::vector<std::exception_ptr> probe_each_in_child(const std::vector<std::filesystem::path>& files,
                                                    const std::function<void(std::size_t)>& read,
                                                    double timeout_seconds) {
  timeout_seconds = std::max(timeout_seconds, 1e-6);  // a zero timer would set no limit
  std::vector<std::exception_ptr> out(files.size());
  bool alone = false;  // the next child reads one file only
  for (std::size_t next = 0; next < files.size();) {
    const std::size_t end = alone ? next + 1 : files.size();
    const std::filesystem::path& first = files[next];
    int fds[2];
    if (::pipe(fds) != 0)
      throw IoError(first.string() + ": cannot create pipe: " + std::strerror(errno));
    const pid_t pid = ::fork();
    if (pid < 0) {
      ::close(fds[0]);
      ::close(fds[1]);
      throw IoError(first.string() + ": cannot fork to read safely: " + std::strerror(errno));
    }
    if (pid == 0) {
      restore_default_fault_handling();
      ::close(fds[0]);
      child(fds[1], next, end, read, timeout_seconds);
    }
    ::close(fds[1]);
    std::string text;
    char buffer[4096];
    for (ssize_t n; (n = ::read(fds[0], buffer, sizeof buffer)) != 0;) {
      if (n < 0) {
        if (errno == EINTR) continue;
        break;
      }
      text.append(buffer, static_cast<std::size_t>(n));
    }
    ::close(fds[0]);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0) {  // [next, end) read cleanly
      next = end;
      alone = false;
      continue;
    }
    // The files before the one it was at read cleanly (a child that died
    // before its first line died on its first file).
    const ChildReport report = parse_report(text);
    const std::size_t at = std::clamp(report.at.value_or(next), next, end - 1);
    if (at > next) {
      // Earlier reads in the same child may have damaged its memory without
      // a crash: the verdict on this file is what it does in a child alone.
      next = at;
      alone = true;
      continue;
    }
    out[at] = failure(files[at], status, report.message, timeout_seconds);
    next = at + 1;
    alone = false;
  }
  return out;
}

void probe_in_child(const std::filesystem::path& file, const std::function<void()>& read,
                    double timeout_seconds) {
  const std::exception_ptr e = probe_each_in_child(
                                   {file}, [&](std::size_t) { read(); }, timeout_seconds)
                                   .front();
  if (e) std::rethrow_exception(e);
}

}  // namespace cnclab
