#pragma once
// Atomic file output: write to a temporary name in the destination folder,
// then fsync and rename over the final name. A reader sees either the old
// file or the complete new one, never a torn write; a crash leaves at most a
// temporary, recognisable by its name:
//
//   <dir>/.<final-name>.partial-<pid>-<16 hex digits>
//
// Every command that scans folders for results or datasets skips such names
// (is_partial_path). The leading dot also hides them from `ls` and globs.
//
// Usage: AtomicOutput out(path); write out.temp_path() and close it;
// out.commit(). Leaving the scope without commit() removes the temporary, so
// an abandoned or failed write leaves the previous file at `path` untouched.
#include <filesystem>
#include <string>

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

// True if the file name has the temporary's pattern above.
bool is_partial_path(const std::filesystem::path& path);

}  // namespace cnclab
