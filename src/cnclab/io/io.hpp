#pragma once
// Module io: HDF5 files, atomic writes, file-format markers, provenance.
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/file_format.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/provenance.hpp"
