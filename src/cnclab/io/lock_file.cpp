#include "cnclab/io/lock_file.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sstream>
#include <thread>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// Whether process `pid` of this host has ended: no such process, or a zombie
// (it has exited and waits only for its parent to reap it, which a parent
// that forked it may never do; kill(pid, 0) still succeeds on it). The state
// is the field after the command's closing parenthesis in /proc/PID/stat
// (proc(5)); the command may itself hold ')' and spaces.
bool process_ended(long pid) {
  if (::kill(static_cast<pid_t>(pid), 0) != 0) return errno == ESRCH;
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  const std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto paren = stat.rfind(')');
  if (paren == std::string::npos || paren + 2 >= stat.size()) return false;
  const char state = stat[paren + 2];
  return state == 'Z' || state == 'X';
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A holder on this host that no longer runs. An empty or partly written
// file (its holder is between create and write) is not stale.
bool stale(const std::string& holder) {
  std::istringstream in(holder);
  std::string host;
  long pid = 0;
  if (!(in >> host >> pid) || pid <= 0) return false;
  if (LockFile::holder_text(pid) != holder) return false;  // another host
  return process_ended(pid);
}

// Creates the lock file holding `me`: true; false when it exists already.
bool create(const fs::path& path, const std::string& me) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    if (errno == EEXIST) return false;
    throw IoError(path.string() + ": cannot create lock file: " + std::strerror(errno));
  }
  const bool written = ::write(fd, me.data(), me.size()) == static_cast<ssize_t>(me.size());
  ::close(fd);
  if (!written) {
    ::unlink(path.c_str());
    throw IoError(path.string() + ": cannot write the lock file");
  }
  return true;
}

}  // namespace

std::string LockFile::holder_text(long pid) {
  char host[256] = {};
  ::gethostname(host, sizeof host - 1);
  return std::string(host) + " " + std::to_string(pid) + "\n";
}

std::string LockFile::describe_holder(const std::string& holder_text) {
  std::istringstream in(holder_text);
  std::string host;
  long pid = 0;
  if (!(in >> host >> pid)) return "unknown holder";
  return "host " + host + ", pid " + std::to_string(pid);
}

std::optional<LockFile> LockFile::try_lock(const fs::path& path, std::string* holder) {
  std::error_code ec;
  fs::create_directories(path.parent_path(), ec);
  const std::string me = holder_text(::getpid());
  // Each round creates the file, finds a live holder, or removes a stale
  // one; a stale file re-created at once by another caller is theirs.
  for (;;) {
    if (create(path, me)) return LockFile(path);
    std::string text = read_text(path);
    // Empty: its holder is between create and write; a moment gives its name.
    for (int i = 0; i < 20 && text.empty() && fs::exists(path, ec); ++i) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      text = read_text(path);
    }
    if (!stale(text)) {
      // Gone between open and read: try again; else held.
      if (!fs::exists(path, ec)) continue;
      if (holder) *holder = text.substr(0, text.find('\n'));
      return std::nullopt;
    }
    if (read_text(path) == text) ::unlink(path.c_str());
  }
}

LockFile::LockFile(const fs::path& path, std::ostream* log) {
  auto next_note = std::chrono::steady_clock::now() + std::chrono::minutes(1);
  for (int wait_ms = 20;; wait_ms = std::min(wait_ms * 2, 500)) {
    std::string holder;
    if (auto lock = try_lock(path, &holder)) {
      *this = std::move(*lock);
      return;
    }
    if (log && std::chrono::steady_clock::now() > next_note) {
      *log << "note: waiting for " << path.string() << " (held by " << describe_holder(holder)
           << "); if that process is gone, remove the file\n";
      next_note = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
  }
}

std::string LockFile::holder(const fs::path& path) {
  const std::string text = read_text(path);
  return text.substr(0, text.find('\n'));
}

bool LockFile::held(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) return false;
  return !stale(read_text(path));
}

LockFile::LockFile(LockFile&& other) noexcept : path_(std::move(other.path_)) {
  other.path_.clear();
}

LockFile& LockFile::operator=(LockFile&& other) noexcept {
  if (this != &other) {
    release();
    path_ = std::move(other.path_);
    other.path_.clear();
  }
  return *this;
}

LockFile::~LockFile() {
  release();
}

void LockFile::release() noexcept {
  if (!path_.empty()) ::unlink(path_.c_str());
  path_.clear();
}

}  // namespace cnclab
