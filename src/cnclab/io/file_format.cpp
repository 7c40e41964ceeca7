#include "cnclab/io/file_format.hpp"

#include <cstdint>

#include "cnclab/core/error.hpp"
#include "cnclab/io/atomic_file.hpp"

namespace cnclab {

void write_format(H5File& file, const std::string& format, int version) {
  file.set_attribute("/", "format", format);
  file.set_attribute("/", "format_version", std::int64_t{version});
}

void mark_complete(H5File& file) {
  file.set_attribute("/", "complete", std::int64_t{1});
}

void require_format(const H5File& f, const std::string& format, int version) {
  require_format(f, format, version, version);
}

int require_format(const H5File& f, const std::string& format, int oldest, int newest) {
  const std::string file = f.path().string();
  // A temporary of an atomic write may hold complete content (killed between
  // close and rename) but was never committed: never a file to read.
  if (is_partial_path(f.path())) {
    throw IoError(file + ": a partial file of an interrupted write, not a " + format + " file");
  }
  if (!f.has_attribute("/", "format") || f.attribute_string("/", "format") != format) {
    throw IoError(file + ": not a " + format + " file (root attribute format)");
  }
  const auto found = f.attribute_int("/", "format_version");
  if (found < oldest || found > newest) {
    throw IoError(file + ": unsupported format_version " + std::to_string(found) + " (expected " +
                  (oldest == newest ? std::to_string(newest)
                                    : std::to_string(oldest) + " to " + std::to_string(newest)) +
                  ")");
  }
  if (!f.has_attribute("/", "complete") || f.attribute_int("/", "complete") != 1) {
    throw IoError(file + ": incomplete file (interrupted write?)");
  }
  return static_cast<int>(found);
}

}  // namespace cnclab
