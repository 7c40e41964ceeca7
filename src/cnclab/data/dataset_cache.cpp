#include "cnclab/data/dataset_cache.hpp"

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
#include "cnclab/core/hash.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/constant_targets.hpp"
#include "cnclab/data/dataset_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// Whether process `pid` of this host has ended: no such process, or a zombie
// (it has exited and waits only for its parent to reap it, which a parent
// that forked it may never do; kill(pid, 0) still succeeds on it). The state
// is the field after the command's closing parenthesis in /proc/PID/stat
// (proc(5)); the command may itself hold ')' and spaces.
bool dataset_lock_holder_ended(long pid) {
  if (::kill(static_cast<pid_t>(pid), 0) != 0) return errno == ESRCH;
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  const std::string stat((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto paren = stat.rfind(')');
  if (paren == std::string::npos || paren + 2 >= stat.size()) return false;
  const char state = stat[paren + 2];
  return state == 'Z' || state == 'X';
}

// An exclusive lock held as a lock file for the object's lifetime: created
// with O_CREAT | O_EXCL (atomic on local filesystems and NFSv3+, where
// flock(2) may be local to one client) and holding "<host> <pid>\n" of its
// holder; removed on destruction. A waiter polls. A lock file whose holder is
// on this host and no longer runs (killed before it removed its lock, or a
// zombie) is stale and removed; a holder on another host cannot be checked and is waited
// for, with a note every minute naming the file to remove if that node died.
// Two waiters removing the same stale lock at once may both generate: the
// dataset is then written twice, atomically and with the same content.
class DatasetLockFile {
 public:
  DatasetLockFile(const fs::path& path, std::ostream* log) : path_(path) {
    std::error_code ec;
    fs::create_directories(path.parent_path(), ec);
    const std::string me = holder_text(::getpid());
    auto next_note = std::chrono::steady_clock::now() + std::chrono::minutes(1);
    for (int wait_ms = 20;; wait_ms = std::min(wait_ms * 2, 500)) {
      const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
      if (fd >= 0) {
        const bool written = ::write(fd, me.data(), me.size()) == static_cast<ssize_t>(me.size());
        ::close(fd);
        if (!written) {
          ::unlink(path.c_str());
          throw IoError(path.string() + ": cannot write the lock file");
        }
        return;
      }
      if (errno != EEXIST) {
        throw IoError(path.string() + ": cannot create lock file: " + std::strerror(errno));
      }
      const std::string holder = read_holder();
      if (stale(holder)) {
        if (read_holder() == holder) ::unlink(path.c_str());
        continue;
      }
      if (log && std::chrono::steady_clock::now() > next_note) {
        *log << "note: waiting for " << path.string() << " (held by " << holder
             << "); if that process is gone, remove the file\n";
        next_note = std::chrono::steady_clock::now() + std::chrono::minutes(1);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(wait_ms));
    }
  }
  ~DatasetLockFile() { ::unlink(path_.c_str()); }
  DatasetLockFile(const DatasetLockFile&) = delete;
  DatasetLockFile& operator=(const DatasetLockFile&) = delete;

  // "<host> <pid>\n".
  static std::string holder_text(long pid) {
    char host[256] = {};
    ::gethostname(host, sizeof host - 1);
    return std::string(host) + " " + std::to_string(pid) + "\n";
  }

 private:
  std::string read_holder() const {
    std::ifstream in(path_);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return text;
  }

  // A holder on this host that no longer runs. An empty or partly written
  // file (its holder is between create and write) is not stale.
  static bool stale(const std::string& holder) {
    std::istringstream in(holder);
    std::string host;
    long pid = 0;
    if (!(in >> host >> pid) || pid <= 0) return false;
    if (holder_text(pid) != holder) return false;  // another host
    return dataset_lock_holder_ended(pid);
  }

  fs::path path_;
};

// The cached dataset at `path` if it is readable and made by this generator
// config; nothing otherwise (with a note why).
bool read_cached(CachedDataset& out, const DatasetGenerator& generator,
                 const std::string& config_text, std::ostream* log) {
  std::error_code ec;
  if (!fs::exists(out.path, ec)) return false;
  try {
    Dataset cached = read_dataset(out.path);
    if (cached.generator == generator.name() && cached.generator_config == config_text) {
      out.dataset = std::move(cached);
      out.content_hash = out.dataset.content_hash();
      out.reused = true;
      return true;
    }
    if (log) *log << "note: " << out.path.string() << " holds another dataset; regenerating\n";
  } catch (const IoError& e) {
    if (log) *log << "note: cached dataset unusable (" << e.what() << "); regenerating\n";
  }
  return false;
}

}  // namespace

Dataset generate_dataset(const DatasetSpec& spec, std::uint64_t seed,
                         const ProgressCallback& progress) {
  Rng rng(seed);
  return spec.generator->generate(rng, progress);
}

// The cache key's text; a generator that ignores its seed gets none, so every
// seed shares one cached dataset (issue 22: identical data cached twice).
std::string dataset_config_text(const DatasetGenerator& generator, std::uint64_t seed) {
  return generator.options_yaml() + "generator_version: " + std::to_string(generator.version()) +
         "\n" + (generator.uses_seed() ? "seed: " + std::to_string(seed) + "\n" : "");
}

fs::path dataset_cache_file(const DatasetSpec& spec, std::uint64_t seed, const fs::path& dir) {
  const DatasetGenerator& generator = *spec.generator;
  const std::string key = Hasher()
                              .add(generator.name())
                              .add(std::string_view("\n"))
                              .add(dataset_config_text(generator, seed))
                              .hex();
  return dir / (generator.name() + "-" + key + ".h5");
}

CachedDataset obtain_dataset(const DatasetSpec& spec, std::uint64_t seed, const fs::path& dir,
                             std::ostream* log, bool regenerate, const ProgressCallback& progress) {
  // The key must not require generating. The generator's options, version
  // and seed are also stored in the dataset file, so the file says how to
  // make it again.
  const DatasetGenerator& generator = *spec.generator;
  const std::string config_text = dataset_config_text(generator, seed);
  CachedDataset out;
  out.path = dataset_cache_file(spec, seed, dir);
  const std::string stem = out.path.stem().string();

  // Unlocked first: a cache hit (the common case) costs no lock.
  if (!regenerate && read_cached(out, generator, config_text, nullptr)) return out;
  const DatasetLockFile lock(dir / ("." + stem + ".lock"), log);
  if (!regenerate && read_cached(out, generator, config_text, log)) return out;
  out.dataset = generate_dataset(spec, seed, progress);
  if (log) {
    for (const auto& t : constant_targets(out.dataset, generator.target_resolution())) {
      *log << "warning: dataset " << out.path.filename().string() << ": " << constant_target_text(t)
           << "\n";
    }
  }
  out.dataset.generator_config = config_text;
  out.content_hash = out.dataset.content_hash();
  write_dataset(out.path, out.dataset);
  return out;
}

}  // namespace cnclab
