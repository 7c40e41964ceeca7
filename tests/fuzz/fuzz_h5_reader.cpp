// Fuzz target: bytes written to a temporary file, then opened by the result
// and dataset readers. Contract: success, or cnclab::IoError naming the file.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/experiment/result_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("cnclab_fuzz_" + std::to_string(::getpid()) + ".h5");
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  const auto check = [&](auto&& read) {
    try {
      read();
    } catch (const cnclab::IoError& e) {
      if (std::string(e.what()).find(path.string()) == std::string::npos) {
        std::fprintf(stderr, "IoError without the file name: %s\n", e.what());
        std::abort();
      }
    }
  };
  check([&] { cnclab::read_result(path); });
  check([&] { cnclab::read_dataset(path); });
  std::filesystem::remove(path);
  return 0;
}
