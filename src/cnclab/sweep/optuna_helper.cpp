#include "cnclab/sweep/optuna_helper.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "cnclab/core/error.hpp"
#include "cnclab/core/share_paths.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

constexpr const char* kScript = "scripts/optuna/optuna_helper.py";

// A private temporary file (mkstemp), unlinked when `keep_name` is false.
int temp_file(std::string& name, bool keep_name) {
  std::string pattern = (fs::temp_directory_path() / "cnclab-optuna-XXXXXX").string();
  const int fd = ::mkstemp(pattern.data());
  if (fd < 0) throw IoError(std::string("cannot create a temporary file: ") + std::strerror(errno));
  ::fcntl(fd, F_SETFD, FD_CLOEXEC);
  name = pattern;
  if (!keep_name) ::unlink(pattern.c_str());
  return fd;
}

// The request lock (optuna_helper.hpp): a write lock on the whole file.
class RequestLock {
 public:
  explicit RequestLock(int fd) : fd_(fd) { set(F_WRLCK); }
  ~RequestLock() { set(F_UNLCK); }
  RequestLock(const RequestLock&) = delete;
  RequestLock& operator=(const RequestLock&) = delete;

 private:
  void set(short type) {
    struct flock l {};
    l.l_type = type;
    l.l_whence = SEEK_SET;
    while (::fcntl(fd_, F_SETLKW, &l) != 0 && errno == EINTR) {
    }
  }
  int fd_;
};

}  // namespace

void OptunaHelperOptions::validate() const {
  if (!(timeout_seconds > 0)) {
    throw OptionError("timeout_seconds", std::to_string(timeout_seconds), "must be > 0");
  }
}

fs::path default_optuna_python() {
  const char* env = std::getenv("CNCLAB_PYTHON");
  return env && *env ? fs::path(env) : fs::path("/usr/bin/python3");
}

OptunaHelper::OptunaHelper(OptunaHelperOptions options) : options_(std::move(options)) {
  options_.validate();
  if (options_.interpreter.empty()) options_.interpreter = default_optuna_python();
  if (options_.script.empty()) options_.script = require_shared(kScript);
  if (::access(options_.interpreter.c_str(), X_OK) != 0) {
    throw ConfigError(options_.purpose +
                      " needs Python with Optuna: " + options_.interpreter.string() +
                      " is not an executable (set CNCLAB_PYTHON to the Python that has the "
                      "package python3-optuna, or install it: apt-get install python3-optuna)");
  }
  int sv[2];
  if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv) != 0) {
    throw Error(std::string("cannot start the Optuna helper: socketpair: ") + std::strerror(errno));
  }
  std::string err_name;
  const int err_fd = temp_file(err_name, true);
  stderr_file_ = err_name;
  std::string lock_name;
  lock_fd_ = temp_file(lock_name, false);
  const pid_t parent = ::getpid();
  pid_ = ::fork();
  if (pid_ < 0) {
    ::close(sv[0]), ::close(sv[1]), ::close(err_fd);
    throw Error(std::string("cannot start the Optuna helper: fork: ") + std::strerror(errno));
  }
  if (pid_ == 0) {
    // The helper ends with its sweep (and reads end of input when it closes).
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (::getppid() != parent) ::_exit(127);
    ::dup2(sv[1], 0);
    ::dup2(sv[1], 1);
    ::dup2(err_fd, 2);
    sigset_t none;
    sigemptyset(&none);
    ::sigprocmask(SIG_SETMASK, &none, nullptr);
    const std::string python = options_.interpreter.string(), script = options_.script.string();
    ::execl(python.c_str(), python.c_str(), "-u", script.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(sv[1]);
  ::close(err_fd);
  to_helper_ = from_helper_ = sv[0];
  // A helper that cannot import Optuna answers before it reads (and may be
  // gone already): a failed send is left to the read below.
  const std::string hello_line = "{\"op\": \"hello\"}\n";
  (void)::send(to_helper_, hello_line.data(), hello_line.size(), MSG_NOSIGNAL);
  nlohmann::json hello;
  try {
    hello = nlohmann::json::parse(read_line());
  } catch (const nlohmann::json::exception&) {
    died("its first answer is not JSON");
  }
  if (hello.value("ok", false)) return;
  const std::string missing = hello.value("missing", "");
  const std::string error = hello.value("error", "no reason given");
  if (!missing.empty()) {
    throw ConfigError(options_.purpose + " needs Optuna, which " + options_.interpreter.string() +
                      " cannot import (" + error + "): install the package " + missing +
                      " (apt-get install " + missing +
                      " python3-cmaes python3-sklearn, as scripts/setup does), or set "
                      "CNCLAB_PYTHON to a Python that has it; grid and random search need "
                      "neither");
  }
  died("it did not start: " + error);
}

OptunaHelper::~OptunaHelper() {
  if (lock_fd_ >= 0) ::close(lock_fd_);
  if (to_helper_ >= 0) ::close(to_helper_);  // end of input: the helper exits
  if (pid_ > 0) {
    using Clock = std::chrono::steady_clock;
    const auto until = Clock::now() + std::chrono::seconds(10);
    int status = 0;
    while (::waitpid(pid_, &status, WNOHANG) == 0) {
      if (Clock::now() > until) {
        ::kill(pid_, SIGKILL);
        ::waitpid(pid_, &status, 0);
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  }
  std::error_code ec;
  if (!stderr_file_.empty()) fs::remove(stderr_file_, ec);
}

std::string OptunaHelper::stderr_tail() const {
  std::ifstream in(stderr_file_);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  constexpr std::size_t kTail = 1500;
  if (text.size() > kTail) text = "..." + text.substr(text.size() - kTail);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

void OptunaHelper::died(const std::string& what) {
  std::ostringstream m;
  m << "the Optuna helper (" << options_.interpreter.string() << " " << options_.script.string()
    << ", pid " << pid_ << ") failed: " << what;
  int status = 0;
  const pid_t r = pid_ > 0 ? ::waitpid(pid_, &status, WNOHANG) : -1;
  if (r == pid_) {
    if (WIFEXITED(status)) m << "; it exited with status " << WEXITSTATUS(status);
    if (WIFSIGNALED(status)) m << "; it was killed by signal " << WTERMSIG(status);
    pid_ = -1;
  }
  if (const std::string tail = stderr_tail(); !tail.empty()) m << "; its stderr: " << tail;
  throw Error(m.str());
}

std::string OptunaHelper::read_line() {
  using Clock = std::chrono::steady_clock;
  const auto until = Clock::now() + std::chrono::duration_cast<Clock::duration>(
                                        std::chrono::duration<double>(options_.timeout_seconds));
  for (;;) {
    if (const auto nl = buffer_.find('\n'); nl != std::string::npos) {
      std::string line = buffer_.substr(0, nl);
      buffer_.erase(0, nl + 1);
      return line;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(until - Clock::now());
    if (left.count() <= 0) {
      if (pid_ > 0) ::kill(pid_, SIGKILL);
      died("no answer within " + std::to_string(options_.timeout_seconds) + " s (killed)");
    }
    pollfd p{from_helper_, POLLIN, 0};
    const int n = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (n < 0 && errno != EINTR) died(std::string("poll: ") + std::strerror(errno));
    if (n <= 0) continue;
    char chunk[4096];
    const ssize_t got = ::read(from_helper_, chunk, sizeof chunk);
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) {
      // Give the ended helper a moment to be reapable, for its exit status.
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      died("it closed its output (ended) before answering");
    }
    buffer_.append(chunk, static_cast<std::size_t>(got));
  }
}

nlohmann::json OptunaHelper::request_line(const std::string& line) {
  if (to_helper_ < 0) throw Error("the Optuna helper is not running");
  const RequestLock lock(lock_fd_);
  const std::string text = line + "\n";
  std::size_t sent = 0;
  while (sent < text.size()) {
    const ssize_t n = ::send(to_helper_, text.data() + sent, text.size() - sent, MSG_NOSIGNAL);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) died(std::string("cannot send it a message: ") + std::strerror(errno));
    sent += static_cast<std::size_t>(n);
  }
  const std::string answer = read_line();
  try {
    nlohmann::json j = nlohmann::json::parse(answer);
    if (!j.is_object()) died("its answer is not a JSON object: " + answer);
    return j;
  } catch (const nlohmann::json::exception&) {
    died("its answer is not JSON: " + answer.substr(0, 200));
  }
}

nlohmann::json OptunaHelper::request(const nlohmann::json& message, bool config_error) {
  nlohmann::json answer = request_line(message.dump());
  if (answer.value("ok", false)) return answer;
  const std::string text = "Optuna helper, " + message.value("op", std::string("?")) + ": " +
                           answer.value("error", std::string("no reason given"));
  if (config_error) throw ConfigError(text);
  throw Error(text);
}

}  // namespace cnclab
