#pragma once
// TttrrOptions from YAML (configs/machines/tttrr_*.yaml) and back. Angles are
// degrees in YAML, radians inside:
//   offset_d: 100            # mm
//   limits: {x: [-400, 400], y: [-300, 300], z: [-300, 300],   # mm
//            a: [-110, 110], c: [-180, 180]}                    # deg
//   c_at_singularity: 0      # deg
//   singular_tolerance: 1e-12
//   unit_tolerance: 1e-9
#include <string>

#include "cnclab/core/config.hpp"
#include "cnclab/kinematics/tttrr.hpp"

namespace cnclab {

// Strict: unknown keys and bad values are ConfigErrors naming the position.
TttrrOptions read_tttrr_options(const ConfigReader& machine);

// The resolved options as a YAML block map that read_tttrr_options() reads
// back to the same values (degrees converted exactly as written).
std::string tttrr_options_yaml(const TttrrOptions& options);

}  // namespace cnclab
