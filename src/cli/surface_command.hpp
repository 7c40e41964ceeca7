#pragma once
// `cnclab surface`: the faces of a STEP/IGES file, and our YAML surfaces as
// STEP/IGES B-spline faces (issue 19 item 2; cnclab/cad/).
#include <filesystem>
#include <ostream>

namespace cnclab {

// `surface show FILE`: one row per face (index, type, degrees, parameter
// bounds, area, bounding box).
int surface_show_command(const std::filesystem::path& file, std::ostream& out);

// `surface export SURFACE.yaml --out FILE.step|.stp|.iges|.igs`: the surface
// (configs/surfaces/*.yaml layout) as one B-spline face, written atomically.
int surface_export_command(const std::filesystem::path& surface_yaml,
                           const std::filesystem::path& out_file, std::ostream& log);

// `surface example-part --out FILE [--freeform SURFACE.yaml]`: the example
// part of experiments/step_error/cad_example.yaml (cad/cad_export.hpp).
int surface_example_part_command(const std::filesystem::path& freeform_yaml,
                                 const std::filesystem::path& out_file, std::ostream& log);

}  // namespace cnclab
