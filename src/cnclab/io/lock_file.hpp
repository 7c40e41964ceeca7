#pragma once
// An exclusive lock held as a lock file, safe on NFS: the file is created
// with O_CREAT | O_EXCL (atomic on local file systems and NFSv3+, where
// flock(2) may be local to one client) and holds "<host> <pid>\n" of its
// holder; it is removed when the lock is released. What the dataset cache
// (one producer per dataset) and sweeps (one writer per trial) use.
//
// Stale locks: a lock file whose holder is on this host and no longer runs
// (killed before it removed its lock, or a zombie) is removed by the next
// caller. A holder on another host cannot be checked and is waited for; the
// blocking form prints a note every minute naming the file to remove if that
// node died. Two callers removing the same stale lock at once may both take
// it: what each then does must be safe to do twice (atomic writes).
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>

namespace cnclab {

class LockFile {
 public:
  // Waits until the lock at `path` is this process's (polling, 20 ms
  // growing to 0.5 s). Notes go to `log` (may be nullptr). Creates the
  // folder if needed. IoError when the file cannot be created for another
  // reason than being held.
  LockFile(const std::filesystem::path& path, std::ostream* log);

  // The lock if it is free (or its holder ended on this host); nullopt when
  // a live holder (or one on another host) has it, with its "<host> <pid>"
  // line in `holder` if given. IoError as above.
  static std::optional<LockFile> try_lock(const std::filesystem::path& path,
                                          std::string* holder = nullptr);

  // Whether someone holds the lock at `path` now: the file exists and its
  // holder is not known to have ended.
  static bool held(const std::filesystem::path& path);

  // The "<host> <pid>" line of the lock file at `path` ("" when none).
  static std::string holder(const std::filesystem::path& path);

  // "host h, pid 123" from a lock file's text (as given when unreadable).
  static std::string describe_holder(const std::string& holder_text);

  LockFile(LockFile&& other) noexcept;
  LockFile& operator=(LockFile&& other) noexcept;
  LockFile(const LockFile&) = delete;
  LockFile& operator=(const LockFile&) = delete;
  ~LockFile();  // removes the lock file

  const std::filesystem::path& path() const { return path_; }

  // "<host> <pid>\n": what a lock file of process `pid` on this host holds.
  static std::string holder_text(long pid);

 private:
  explicit LockFile(std::filesystem::path path) : path_(std::move(path)) {}
  void release() noexcept;

  std::filesystem::path path_;  // empty: moved from
};

}  // namespace cnclab
