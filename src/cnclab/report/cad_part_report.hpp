#pragma once
// `cnclab surface show`'s report of a STEP/IGES file's faces
// (cad/cad_faces.hpp summarise_cad_part).
#include <filesystem>
#include <ostream>

#include "cnclab/cad/cad_faces.hpp"

namespace cnclab {

// The file's unit and writer and the probe path of the verdicts (`path`),
// then one row per face (type, degrees, trimmed, holes, solid, normal along
// the tool axis, smallest radius of curvature, usable as is or why not, share
// left with `unreachable: clip`, area, bounding box); `why`: each refusal's
// message after the table.
void print_cad_part(const std::filesystem::path& file, const CadPartSummary& part,
                    const ToolPathOptions& path, bool why, std::ostream& out);

}  // namespace cnclab
