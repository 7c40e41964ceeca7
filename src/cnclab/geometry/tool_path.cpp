#include "cnclab/geometry/tool_path.hpp"

#include <cmath>
#include <cstdio>

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
  std::vector<std::string> axis_text;
  for (double a : tool_axis) axis_text.push_back(shortest_double(a));
  const std::string axis = std::string("[").append(join(axis_text, ", ")).append("]");
  if (tool_axis.size() != 3) throw OptionError("tool_axis", axis, "must be [x, y, z]");
  const Eigen::Vector3d a(tool_axis[0], tool_axis[1], tool_axis[2]);
  if (!a.allFinite() || !(a.norm() > 0.0)) {
    throw OptionError("tool_axis", axis, "must be a finite direction of non-zero length");
  }
  if (!(max_normal_angle > 0.0 && max_normal_angle <= 90.0)) {
    throw OptionError("max_normal_angle", shortest_double(max_normal_angle),
                      "must be in (0, 90] degrees (the normal's largest angle from the tool axis)");
  }
}

Eigen::Vector3d ToolPathOptions::unit_tool_axis() const {
  return Eigen::Vector3d(tool_axis[0], tool_axis[1], tool_axis[2]).normalized();
}

namespace {

// The parameter range [first, last] across the lines (fixed) or along them (t).
std::pair<double, double> range(const NurbsSurface& s, bool along_u) {
  return along_u ? std::pair{s.knots_u.front(), s.knots_u.back()}
                 : std::pair{s.knots_v.front(), s.knots_v.back()};
}

double grid_value(std::pair<double, double> r, std::size_t i, std::size_t n) {
  if (i + 1 == n) return r.second;
  return r.first + (r.second - r.first) * static_cast<double>(i) / static_cast<double>(n - 1);
}

}  // namespace

double tool_path_fixed(const NurbsSurface& s, const ToolPathOptions& o, std::size_t line) {
  return grid_value(range(s, o.feed == FeedDirection::v), line, o.lines);
}

double tool_path_t(const NurbsSurface& s, const ToolPathOptions& o, std::size_t k) {
  return grid_value(range(s, o.feed == FeedDirection::u), k, o.points_per_line);
}

Eigen::Vector2d ToolPathLine::uv(double t_value) const {
  return feed == FeedDirection::u ? Eigen::Vector2d(t_value, fixed)
                                  : Eigen::Vector2d(fixed, t_value);
}

std::string ToolPathLine::label() const {
  char value[32];
  std::snprintf(value, sizeof value, "%.6g", fixed);
  // (append, not operator+: GCC 12 -Wrestrict false positive on "x" + to_string)
  return std::string("line ")
      .append(std::to_string(index))
      .append(feed == FeedDirection::u ? " (v = " : " (u = ")
      .append(value)
      .append(")");
}

std::size_t ToolPath::points() const {
  return lines.empty() ? 0 : lines.size() * lines.front().t.size();
}

}  // namespace cnclab
