#pragma once
// (Internal to the cad module: OCCT types.) What CadPart holds.
#include <TopoDS_Face.hxx>
#include <vector>

#include "cnclab/cad/cad_surface.hpp"
#include "cnclab/cad/occt_shape_io.hpp"

namespace cnclab {

struct CadShapeData {
  occt::CadShape shape;
  // Per face (file order): whether it bounds a solid through a closed shell,
  // its orientation in that shell then making its normal point outward.
  std::vector<char> of_solid;
};

namespace occt {

// The part's face `face` (1-based), ConfigError naming the file when out of range.
const TopoDS_Face& part_face(const CadPart& part, int face);

}  // namespace occt
}  // namespace cnclab
