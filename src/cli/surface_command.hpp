#pragma once
// `cnclab surface`: the faces of a STEP/IGES file and whether each gives a
// tool path, and surfaces (YAML, or a face of a CAD file) as STEP/IGES
// files (cnclab/cad/).
#include <filesystem>
#include <ostream>

#include "cnclab/cad/cad_faces.hpp"

namespace cnclab {

// `surface show FILE`: the file's unit and writer, then one row per face
// (type, degrees, trimmed, holes, solid, normal along the tool axis, smallest
// radius of curvature, usable as is or why not, share left with
// `unreachable: clip`, area, bounding box); `why`: each refusal's message.
int surface_show_command(const std::filesystem::path& file, const CadShowOptions& options, bool why,
                         std::ostream& out);

// `surface export SOURCE --out FILE.step|.stp|.iges|.igs [--face N]`: a YAML
// surface (configs/surfaces/*.yaml layout) as one B-spline face, or face N
// of a STEP/IGES file as a NURBS face with its trims, written atomically.
int surface_export_command(const std::filesystem::path& source, int face,
                           const CadReadOptions& read, const std::filesystem::path& out_file,
                           std::ostream& log);

// `surface example-part --out FILE [--freeform SURFACE.yaml]`: the example
// part of experiments/step_error/cad_example.yaml (cad/cad_export.hpp).
int surface_example_part_command(const std::filesystem::path& freeform_yaml,
                                 const std::filesystem::path& out_file, std::ostream& log);

}  // namespace cnclab
