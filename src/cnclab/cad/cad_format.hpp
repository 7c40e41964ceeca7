#pragma once
// CAD files: STEP (ISO 10303-21) and IGES 5.3 parts read and
// written through Open CASCADE Technology (OCCT 7.6). The build enables them
// when CMake finds OCCT (CNCLAB_WITH_OCCT); without it every reading or
// writing function of this module throws the ConfigError of
// cad_unavailable_message().
//
// Faces are numbered from 1 in the order of TopExp::MapShapes over the file's
// shape (FreeCAD's Face1, Face2, ... number them the same way).
#include <filesystem>
#include <optional>
#include <string>

namespace cnclab {

enum class CadFormat { step, iges };

// .step/.stp -> step, .iges/.igs -> iges (any letter case); otherwise none.
std::optional<CadFormat> cad_format_of(const std::filesystem::path& file);
// ConfigError naming the accepted extensions unless cad_format_of knows `file`.
CadFormat require_cad_format(const std::filesystem::path& file);

// Whether this build reads and writes CAD files.
bool cad_support_available();
// Why it does not, and the Debian package to install.
std::string cad_unavailable_message();

}  // namespace cnclab
