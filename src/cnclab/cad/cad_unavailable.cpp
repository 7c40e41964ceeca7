// The cad module's readers and writers in a build without OCCT: each throws
// the ConfigError of cad_unavailable_message() (exit 2 in the CLI).
#include "cnclab/cad/cad_export.hpp"
#include "cnclab/cad/cad_faces.hpp"
#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/core/error.hpp"

namespace cnclab {

struct CadShapeData {};

CadPart read_cad_part(const std::filesystem::path& file, const CadReadOptions&) {
  require_cad_format(file);  // a wrong file name is said first, as with OCCT
  throw ConfigError(file.string() + ": " + cad_unavailable_message());
}

int CadPart::face_count() const {
  return 0;
}

CadSurface CadPart::face(int) const {
  throw ConfigError(file_name + ": " + cad_unavailable_message());
}

CadPartSummary summarise_cad_part(const std::filesystem::path& file, const CadShowOptions&) {
  require_cad_format(file);
  throw ConfigError(file.string() + ": " + cad_unavailable_message());
}

std::string cad_surface_text(const NurbsSurface&, CadFormat) {
  throw ConfigError(cad_unavailable_message());
}

std::string cad_face_text(const CadPart& part, int, CadFormat) {
  throw ConfigError(part.file_name + ": " + cad_unavailable_message());
}

std::string cad_example_part_text(const NurbsSurface&, CadFormat) {
  throw ConfigError(cad_unavailable_message());
}

}  // namespace cnclab
