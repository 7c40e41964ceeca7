#pragma once
// Reading HDF5 files that may be corrupt or crafted. libhdf5 1.10 is not
// memory-safe on such files (fuzzing found heap overflows in its object-header
// and global-heap parsers), so a reader first runs in a forked child with a
// memory limit and a time limit. Only when the child read the file cleanly
// does the caller read it in-process; a child that crashed, hung or ran out of
// memory becomes an IoError naming the file.
#include <filesystem>
#include <functional>

namespace cnclab {

// Runs `read` in a child process. Returns if it completed; re-throws its
// IoError message; throws IoError for a crash, hang or other exception.
void probe_in_child(const std::filesystem::path& file, const std::function<void()>& read);

}  // namespace cnclab
