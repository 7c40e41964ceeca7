#include "cnclab/cad/cad_format.hpp"

#include <algorithm>
#include <cctype>

#include "cnclab/core/error.hpp"

namespace cnclab {

std::optional<CadFormat> cad_format_of(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".step" || ext == ".stp") return CadFormat::step;
  if (ext == ".iges" || ext == ".igs") return CadFormat::iges;
  return std::nullopt;
}

CadFormat require_cad_format(const std::filesystem::path& file) {
  if (auto f = cad_format_of(file)) return *f;
  throw ConfigError(file.string() + ": not a CAD file name (expected .step, .stp, .iges or .igs)");
}

bool cad_support_available() {
#ifdef CNCLAB_WITH_OCCT
  return true;
#else
  return false;
#endif
}

std::string cad_unavailable_message() {
  return "STEP and IGES surfaces need Open CASCADE, and this cnclab was built without it: "
         "install the Debian package libocct-data-exchange-dev (it brings "
         "libocct-modeling-algorithms-dev, libocct-modeling-data-dev and "
         "libocct-foundation-dev; scripts/setup lists them) and build again";
}

}  // namespace cnclab
