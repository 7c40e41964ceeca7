// Fuzz target: bytes written to a temporary .step and .igs file, then read by
// the CAD readers (cnclab/cad: OCCT's STEP and IGES parsers, the NURBS
// conversion, the face listing). Contract: success, or cnclab::ConfigError
// naming the file; never another exception or a crash. In a build without
// OCCT the readers throw the ConfigError naming the package, which holds too.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cnclab/cad/cad_faces.hpp"
#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/core/error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  for (const char* ext : {".step", ".igs"}) {
    const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                       ("cnclab_fuzz_cad_" + std::to_string(::getpid()) + ext);
    {
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    const auto check = [&](auto&& read) {
      try {
        read();
      } catch (const cnclab::ConfigError& e) {
        if (std::string(e.what()).find(path.string()) == std::string::npos) {
          std::fprintf(stderr, "ConfigError without the file name: %s\n", e.what());
          std::abort();
        }
      }
    };
    check([&] { cnclab::summarise_cad_part(path); });
    check([&] { cnclab::read_cad_surface(path, 1); });
    std::filesystem::remove(path);
  }
  return 0;
}
