#include "cnclab/geometry/surface_config.hpp"

#include "cnclab/core/format.hpp"
#include "cnclab/geometry/bspline_basis.hpp"

namespace cnclab {

NurbsSurface read_nurbs_surface(const ConfigReader& r) {
  using Grid = std::vector<std::vector<std::vector<double>>>;
  NurbsSurface s;
  const auto degree = [&](const std::string& key) {
    const auto d = r.require<std::int64_t>(key);
    r.check(d >= 1 && d <= kMaxBsplineDegree, key,
            "must be in [1, " + std::to_string(kMaxBsplineDegree) + "]");
    return static_cast<int>(d);
  };
  s.degree_u = degree("degree_u");
  s.degree_v = degree("degree_v");
  s.knots_u = r.require<std::vector<double>>("knots_u");
  s.knots_v = r.require<std::vector<double>>("knots_v");
  const auto grid = r.require<Grid>("control_points");
  s.count_u = grid.size();
  s.count_v = grid.empty() ? 0 : grid.front().size();
  for (std::size_t i = 0; i < grid.size(); ++i) {
    r.check(grid[i].size() == s.count_v, "control_points",
            "row " + std::to_string(i) + " has " + std::to_string(grid[i].size()) +
                " points, row 0 has " + std::to_string(s.count_v) + " (rows must be equal)");
    for (std::size_t j = 0; j < grid[i].size(); ++j) {
      r.check(grid[i][j].size() == 3, "control_points",
              "point [" + std::to_string(i) + "][" + std::to_string(j) + "] must be [x, y, z]");
      s.points.emplace_back(grid[i][j][0], grid[i][j][1], grid[i][j][2]);
    }
  }
  if (r.has("weights")) {
    const auto weights = r.require<std::vector<std::vector<double>>>("weights");
    r.check(weights.size() == s.count_u, "weights",
            "must have one row per control-point row (" + std::to_string(s.count_u) + ")");
    for (std::size_t i = 0; i < weights.size(); ++i) {
      r.check(weights[i].size() == s.count_v, "weights",
              "row " + std::to_string(i) + " must have " + std::to_string(s.count_v) + " values");
      s.weights.insert(s.weights.end(), weights[i].begin(), weights[i].end());
    }
  } else {
    s.weights.assign(s.points.size(), 1.0);
  }
  r.validate([&] { s.validate(); });
  return s;
}

namespace {
std::string flow_list(const std::vector<double>& values) {
  std::string out = "[";
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i ? ", " : "") + shortest_double(values[i]);
  }
  return out + "]";
}
}  // namespace

std::string nurbs_surface_yaml(const NurbsSurface& s, const std::string& indent) {
  std::string out = indent + "degree_u: " + std::to_string(s.degree_u) + "\n" + indent +
                    "degree_v: " + std::to_string(s.degree_v) + "\n" + indent +
                    "knots_u: " + flow_list(s.knots_u) + "\n" + indent +
                    "knots_v: " + flow_list(s.knots_v) + "\n" + indent + "control_points:\n";
  for (std::size_t i = 0; i < s.count_u; ++i) {
    out += indent + "  - [";
    for (std::size_t j = 0; j < s.count_v; ++j) {
      const Eigen::Vector3d& p = s.point(i, j);
      out += (j ? ", " : "") + flow_list({p.x(), p.y(), p.z()});
    }
    out += "]\n";
  }
  out += indent + "weights:\n";
  for (std::size_t i = 0; i < s.count_u; ++i) {
    out +=
        indent + "  - " +
        flow_list(std::vector<double>(s.weights.begin() + static_cast<long>(i * s.count_v),
                                      s.weights.begin() + static_cast<long>((i + 1) * s.count_v))) +
        "\n";
  }
  return out;
}

}  // namespace cnclab
