#include "cnclab/geometry/tool_path.hpp"

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

void ToolPathOptions::validate() const {
  if (lines < 2 || lines > 1'000'000) {
    throw OptionError("lines", std::to_string(lines), "must be in [2, 1000000]");
  }
  if (points_per_line < 2 || points_per_line > 1'000'000) {
    throw OptionError("points_per_line", std::to_string(points_per_line),
                      "must be in [2, 1000000] (a segment needs two CC points)");
  }
  if (!(tool_radius > 0.0) || !std::isfinite(tool_radius)) {
    throw OptionError("tool_radius", shortest_double(tool_radius),
                      "must be a finite ball radius > 0 mm");
  }
}

double tool_path_v(const NurbsSurface& s, const ToolPathOptions& o, std::size_t line) {
  const double v0 = s.knots_v.front(), v1 = s.knots_v.back();
  return v0 + (v1 - v0) * static_cast<double>(line) / static_cast<double>(o.lines - 1);
}

double tool_path_u(const NurbsSurface& s, const ToolPathOptions& o, std::size_t k) {
  const double u0 = s.knots_u.front(), u1 = s.knots_u.back();
  const std::size_t m = o.points_per_line;
  return k + 1 == m ? u1 : u0 + (u1 - u0) * static_cast<double>(k) / static_cast<double>(m - 1);
}

ToolPathLine plan_line(const NurbsSurface& s, const ToolPathOptions& o, std::size_t line) {
  ToolPathLine t;
  t.v = tool_path_v(s, o, line);
  t.curve = iso_curve_u(s, t.v);
  t.tool_radius = o.tool_radius;
  const std::size_t m = o.points_per_line;
  t.u.resize(m);
  t.cc.resize(m);
  t.normal.resize(m);
  t.cl.resize(m);
  for (std::size_t k = 0; k < m; ++k) {
    t.u[k] = tool_path_u(s, o, k);
    const SurfaceDerivatives d = surface_derivatives(s, t.u[k], t.v);
    t.cc[k] = d.point;
    t.normal[k] = oriented_unit_normal(d, kToolAxis);
    t.cl[k] = d.point + o.tool_radius * t.normal[k];
  }
  return t;
}

}  // namespace cnclab
