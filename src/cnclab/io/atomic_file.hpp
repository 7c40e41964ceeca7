#pragma once
// Atomic file output: write to a temporary name in the destination folder,
// then fsync and rename over the final name. A reader sees either the old
// file or the complete new one, never a torn write; a crash leaves at most a
// temporary, recognisable by its name, which records its writer:
//
//   <dir>/.<final-name>.partial-<host>-<pid>-<16 hex digits>
//
// <host> is the first label of the writer's host name (letters, digits, '-';
// anything else becomes '_'), <pid> its process id. Names written before the
// host was recorded lack "<host>-". Every command that scans folders for
// results or datasets skips such names (is_partial_path). The leading dot
// also hides them from `ls` and globs. remove_stale_partials removes those
// whose writer is gone.
//
// Usage: AtomicOutput out(path); write out.temp_path() and close it;
// out.commit(). Leaving the scope without commit() removes the temporary, so
// an abandoned or failed write leaves the previous file at `path` untouched.
#include <filesystem>
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace cnclab {

class AtomicOutput {
 public:
  // Creates the parent folder of `final_path` if needed; does not create the
  // temporary itself.
  explicit AtomicOutput(std::filesystem::path final_path);
  ~AtomicOutput();  // removes the temporary unless committed
  AtomicOutput(const AtomicOutput&) = delete;
  AtomicOutput& operator=(const AtomicOutput&) = delete;

  // Where to write.
  const std::filesystem::path& temp_path() const { return temp_; }
  const std::filesystem::path& final_path() const { return final_; }
  // fsync the temporary, rename it over the final path, fsync the folder.
  // Throws IoError; on failure the temporary is removed by the destructor.
  void commit();

 private:
  std::filesystem::path final_;
  std::filesystem::path temp_;
  bool committed_ = false;
};

// Writes `text` to `path` through an AtomicOutput (G-code, reports, tables).
// Throws IoError naming the file; the previous file, if any, is untouched on
// failure.
void write_text_atomically(const std::filesystem::path& path, const std::string& text);

// Makes `to` a copy of the finished file `from`, atomically: a hard link
// when both lie on one file system (the files are never modified in place,
// only replaced by rename, so the two names stay independent), else a byte
// copy. Replaces what was at `to`. Throws IoError naming both files.
void copy_file_atomically(const std::filesystem::path& from, const std::filesystem::path& to);

// True if the file name has the temporary's pattern above (with or without
// the host).
bool is_partial_path(const std::filesystem::path& path);

// The writer recorded in a partial file's name.
struct PartialWriter {
  std::string host;  // "" in the older names without a host
  long long pid = 0;
};
std::optional<PartialWriter> partial_writer(const std::filesystem::path& path);

// This host's name as partial names record it (see above); "localhost" when
// the system has none.
std::string partial_host_name();

// Partial files below the given folders (recursively; a folder that does not
// exist has none) whose writer is certainly gone are removed: written on
// `host` by a process id that does not exist (kill(pid, 0) fails with ESRCH).
// A partial file whose writer may still be writing is never touched: a live
// pid (or one owned by another user), another host (a shard of a sweep on
// another node of a shared file system), or an older name without a host.
struct PartialCleanup {
  std::vector<std::filesystem::path> removed;
  std::vector<long long> removed_pids;  // their writers, sorted, each once
  // Partial files whose writer cannot be checked here: another host's, or
  // the older names without one.
  std::vector<std::filesystem::path> unknown;
  // One line for the user ("" when nothing was removed or left unchecked).
  std::string summary() const;
};
PartialCleanup remove_stale_partials(const std::vector<std::filesystem::path>& folders,
                                     const std::string& host = partial_host_name());
// remove_stale_partials, then its summary() as a line on `log` if not empty
// (at the start of a run, sweep or reproduce, for its results and datasets).
void clean_stale_partials(const std::vector<std::filesystem::path>& folders, std::ostream& log);

}  // namespace cnclab
