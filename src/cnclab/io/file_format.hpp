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
// The same, accepting any format_version in [oldest, newest] (readers that
// still read older layouts); returns the version found.
int require_format(const H5File& file, const std::string& format, int oldest, int newest);

}  // namespace cnclab
