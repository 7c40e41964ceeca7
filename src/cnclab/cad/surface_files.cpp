#include "cnclab/cad/surface_files.hpp"

#include "cnclab/cad/cad_export.hpp"
#include "cnclab/cad/cad_format.hpp"
#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/geometry/surface_config.hpp"
#include "cnclab/io/atomic_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;

namespace {

NurbsSurface load_surface_yaml(const fs::path& file) {
  ConfigDocument doc = ConfigDocument::load(file);
  NurbsSurface s = read_nurbs_surface(doc.root());
  doc.check_all_consumed();
  return s;
}

}  // namespace

std::string export_surface_file(const fs::path& source, int face, const CadReadOptions& read,
                                const fs::path& out_file) {
  const CadFormat format = require_cad_format(out_file);
  if (cad_format_of(source)) {
    if (face < 1) {
      throw ConfigError(source.string() +
                        ": a CAD file's face to export is needed: --face N (faces count from 1; "
                        "`cnclab surface show " +
                        source.string() + "` lists them)");
    }
    const CadPart part = read_cad_part(source, read);
    write_text_atomically(out_file, cad_face_text(part, face, format));
    const CadSurface cad = part.face(face);
    return "wrote " + out_file.string() + " (face " + std::to_string(face) + " of " +
           source.string() + ": a " + cad.surface_type + " as a NURBS face, degrees " +
           std::to_string(cad.surface.degree_u) + " x " + std::to_string(cad.surface.degree_v) +
           ", " + (cad.trimmed ? "trimmed" : "untrimmed") + ", " + std::to_string(cad.holes) +
           " hole" + (cad.holes == 1 ? "" : "s") + ")";
  }
  if (face != 0) {
    throw ConfigError(source.string() + ": --face applies to STEP/IGES files, not a YAML surface");
  }
  const NurbsSurface s = load_surface_yaml(source);
  write_text_atomically(out_file, cad_surface_text(s, format));
  return "wrote " + out_file.string() + " (one B-spline face, degrees " +
         std::to_string(s.degree_u) + " x " + std::to_string(s.degree_v) + ", " +
         std::to_string(s.count_u) + " x " + std::to_string(s.count_v) + " control points)";
}

std::string write_example_part(const fs::path& freeform_yaml, const fs::path& out_file) {
  const CadFormat format = require_cad_format(out_file);
  write_text_atomically(out_file, cad_example_part_text(load_surface_yaml(freeform_yaml), format));
  return "wrote " + out_file.string() + " (4 faces: bspline, cylinder, plane, sphere)";
}

}  // namespace cnclab
