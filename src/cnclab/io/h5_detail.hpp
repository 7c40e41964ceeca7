#pragma once
// Internal to cnclab_io: what h5.cpp (file, structure, writing) and
// h5_read.cpp (reading, attributes) both need. Not part of the public API.
#include <hdf5.h>

#include <cstddef>

#include "cnclab/io/h5.hpp"

namespace cnclab::h5_detail {

// The stored string type: fixed-length, null-padded, `cset` (UTF-8 unless a
// reader copies a stored ASCII type); why never variable-length: see h5.cpp.
H5Handle string_type(std::size_t length, H5T_cset_t cset = H5T_CSET_UTF8);

}  // namespace cnclab::h5_detail
