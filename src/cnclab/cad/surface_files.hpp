#pragma once
// `cnclab surface export` and `cnclab surface example-part`: surfaces
// written as STEP/IGES files (cad_export.hpp), atomically. Each returns the
// line that says what it wrote.
#include <filesystem>
#include <string>

#include "cnclab/cad/cad_surface.hpp"

namespace cnclab {

// A YAML surface (configs/surfaces/*.yaml layout) as one B-spline face, or
// face `face` (from 1) of a STEP/IGES `source` as a NURBS face with its
// trims, into `out_file` (.step, .stp, .iges, .igs). ConfigError for a CAD
// source without a face, or a face given for a YAML source.
std::string export_surface_file(const std::filesystem::path& source, int face,
                                const CadReadOptions& read, const std::filesystem::path& out_file);

// The example part of experiments/step_error/cad_example.yaml (4 faces,
// cad_example_part_text) with `freeform_yaml` as its freeform face.
std::string write_example_part(const std::filesystem::path& freeform_yaml,
                               const std::filesystem::path& out_file);

}  // namespace cnclab
