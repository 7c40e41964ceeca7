#include "cnclab/cad/cad_surface.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

std::string CadSurface::label() const {
  return "face " + std::to_string(face) + " of " + file_name;
}

void CadReadOptions::validate() const {
  if (read_timeout != 0 && !(read_timeout >= 0.001 && read_timeout <= 86'400)) {
    throw OptionError("read_timeout", shortest_double(read_timeout),
                      "must be 0 (by the file's size) or seconds in [0.001, 86400]");
  }
}

double default_read_timeout(std::uintmax_t bytes) {
  constexpr double kBaseSeconds = 60.0, kSecondsPerMb = 10.0;
  const double seconds = kBaseSeconds + kSecondsPerMb * static_cast<double>(bytes) / 1e6;
  return std::min(std::ceil(seconds), 86'400.0);
}

CadSurface read_cad_surface(const std::filesystem::path& file, int face,
                            const CadReadOptions& options) {
  return read_cad_part(file, options).face(face);
}

}  // namespace cnclab
