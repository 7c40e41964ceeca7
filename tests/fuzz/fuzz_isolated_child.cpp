// Fuzz target for the isolated HDF5 read itself (isolated_read.hpp), small
// enough to build with clang in seconds (only cnclab's io and core sources):
// tests/fuzz/check_isolated_child runs it under libFuzzer with ASan and UBSan
// and fails if libFuzzer left any artifact.
//
// An input that starts with the HDF5 signature is walked in the child the
// way a reader would (every group, attribute and dataset through libhdf5).
// Any other input picks, by its first byte, a crash for the child: a wild
// write (SIGSEGV), abort(), a heap overflow ASan reports, an allocation of
// a gigabyte, SIGFPE. Contract: the parent sees success or an IoError, and
// libFuzzer's crash handler, inherited through fork, never runs in the child
// (it would record each crash there as a crash-* finding).
#include <unistd.h>

#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/io/isolated_read.hpp"

namespace {

// Reads everything below `group`; the reader's IoErrors (wrong type, ...)
// are expected on fuzzed files.
void walk(const cnclab::H5File& f, const std::string& group, int depth) {
  if (depth > 8) return;
  for (const auto& name : f.children(group)) {
    const std::string path = (group == "/" ? "/" : group + "/") + name;
    try {
      for (const auto& attr : f.attribute_names(path)) {
        try {
          f.attribute_string(path, attr);
        } catch (const cnclab::IoError&) {
          f.attribute_double(path, attr);
        }
      }
      if (f.is_group(path)) {
        walk(f, path, depth + 1);
      } else {
        try {
          f.read_strings(path);
        } catch (const cnclab::IoError&) {
          f.read_matrix(path);
        }
      }
    } catch (const cnclab::IoError&) {
    }
  }
}

void crash(int kind, std::size_t size) {
  switch (kind) {
    case 0: {
      volatile int* volatile wild = nullptr;
      *wild = 1;
      break;
    }
    case 1:
      std::abort();
    case 2: {
      char* block = static_cast<char*>(std::malloc(8));
      std::memset(block, 0, 9 + size);
      std::free(block);
      break;
    }
    case 3: {
      // Never freed: the child _exits (ASan's free would poison 128 MB of
      // shadow memory).
      void* huge = std::malloc(std::size_t{1} << 30);
      if (huge) std::memset(huge, 1, 4096);
      break;
    }
    case 4:
      std::raise(SIGFPE);
      break;
    default:
      break;
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("cnclab_fuzz_child_" + std::to_string(::getpid()) + ".h5");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  const bool hdf5 = size >= 4 && std::memcmp(data, "\x89HDF", 4) == 0;
  try {
    cnclab::probe_in_child(path, [&] {
      if (hdf5) {
        walk(cnclab::H5File::open_read(path), "/", 0);
      } else if (size > 0) {
        crash(data[0] % 6, size);
      }
    });
  } catch (const cnclab::IoError&) {
    // The contract: a crash, hang or bad file is an IoError. Anything else
    // escapes and libFuzzer records it.
  }
  std::filesystem::remove(path);
  return 0;
}
