#pragma once
// Root attributes that identify a cnclab HDF5 file and mark it complete:
// `format`, `format_version`, and `complete` = 1 written last, so a file
// without it is never taken for a finished one.
#include <string>

#include "cnclab/io/h5.hpp"

namespace cnclab {

void write_format(H5File& file, const std::string& format, int version);
void mark_complete(H5File& file);
// Throws IoError naming the file unless it has this format and version, is
// marked complete, and its name is not a partial name (is_partial_path).
void require_format(const H5File& file, const std::string& format, int version);

}  // namespace cnclab
