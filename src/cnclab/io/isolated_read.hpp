#pragma once
// Reading HDF5 files that may be corrupt or crafted. libhdf5 1.10 is not
// memory-safe on such files (fuzzing found heap overflows in its object-header
// and global-heap parsers), so a reader first runs in a forked child with a
// memory limit and a time limit. Only when the child read the file cleanly
// does the caller read it in-process; a child that crashed, hung or ran out of
// memory becomes an IoError naming the file.
#include <filesystem>
#include <functional>

#include "cnclab/core/error.hpp"

namespace cnclab {

// The child did not finish within its time limit.
class ProbeTimedOut : public IoError {
 public:
  using IoError::IoError;
};

// Runs `read` in a child process. Returns if it completed; re-throws its
// IoError message; throws ProbeTimedOut when it runs longer than
// `timeout_seconds` (wall clock, > 0; a sane HDF5 file reads in
// milliseconds), IoError for a crash or other exception.
void probe_in_child(const std::filesystem::path& file, const std::function<void()>& read,
                    double timeout_seconds = 60);

}  // namespace cnclab
