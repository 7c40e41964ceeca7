#include "cnclab/cad/cad_surface.hpp"

#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

std::string CadSurface::label() const {
  return "face " + std::to_string(face) + " of " + file_name;
}

void check_tool_path_on_face(const CadSurface& cad, const ToolPathOptions& o) {
  if (!cad.boundary) throw Error(cad.label() + ": no face boundary to check the tool path against");
  // The u of the CC points, the same on every line (geometry/tool_path.hpp).
  std::vector<double> us(o.points_per_line);
  for (std::size_t k = 0; k < us.size(); ++k) us[k] = tool_path_u(cad.surface, o, k);
  for (std::size_t line = 0; line < o.lines; ++line) {
    const double v = tool_path_v(cad.surface, o, line);
    for (std::size_t k = 0; k < us.size(); ++k) {
      const double u = us[k];
      if (!cad.boundary->contains(cad.surface, u, v)) {
        const Eigen::Vector3d p = surface_point(cad.surface, u, v);
        throw ConfigError(cad.label() + " (" + cad.surface_type +
                          ") is trimmed and the tool path "
                          "leaves it: line " +
                          std::to_string(line) + ", CC point " + std::to_string(k) + " at (" +
                          shortest_double(p.x()) + ", " + shortest_double(p.y()) + ", " +
                          shortest_double(p.z()) +
                          ") mm lies outside the face's boundary; choose a face whose "
                          "boundary is its parameter rectangle");
      }
    }
  }
}

}  // namespace cnclab
