#pragma once
// Iso-parametric ball-end tool paths (patent 003 step 1, seed 000 "Sample
// construction"): N lines at constant v, M cutter-contact (CC) points per line
// equally spaced in u; the tool side is +z (3-axis machining from above) and
// the cutter location (CL) is the ball centre CC + R n.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "cnclab/geometry/nurbs_curve.hpp"
#include "cnclab/geometry/nurbs_surface.hpp"
#include "cnclab/geometry/step_error.hpp"

namespace cnclab {

// The tool axis of 3-axis machining; surface normals are oriented toward it.
inline const Eigen::Vector3d kToolAxis{0.0, 0.0, 1.0};

struct ToolPathOptions {
  // N, lines at v_l = v_min + (v_max - v_min) l / (N - 1), l = 0..N-1, the
  // feed direction along u (seed 000: 200 lines). >= 2.
  std::size_t lines = 200;
  // M, CC points per line at u_k = u_min + (u_max - u_min) k / (M - 1)
  // (seed 000: 100 CL points per line, so M - 1 = 99 segments). >= 2.
  std::size_t points_per_line = 100;
  // R, ball-end cutter radius [mm] (seed 000 "Sample construction": 5 mm). > 0.
  double tool_radius = 5.0;

  // Throws OptionError naming the field, value and rule.
  void validate() const;
};

// One tool-path line: its CC curve and the CC/CL points along it.
struct ToolPathLine {
  double v = 0.0;                       // the constant parameter of the line
  NurbsCurve curve;                     // exact CC curve u -> S(u, v)
  std::vector<double> u;                // u_k, k = 0..M-1
  std::vector<Eigen::Vector3d> cc;      // S(u_k, v) [mm]
  std::vector<Eigen::Vector3d> normal;  // unit normal at cc, toward the tool (+z)
  std::vector<Eigen::Vector3d> cl;      // cc + R normal [mm]
  double tool_radius = 0.0;             // R [mm]

  // Segment i (CC points i and i + 1, i < u.size() - 1); refers to `curve`.
  StepErrorSegment segment(std::size_t i) const {
    return {&curve, u[i], u[i + 1], cl[i], cl[i + 1], tool_radius};
  }
};

// The constant parameter v_l of line `line` and the parameter u_k of CC point
// `k` (formulas at ToolPathOptions::lines and ::points_per_line; the last
// value is the range end exactly).
double tool_path_v(const NurbsSurface& surface, const ToolPathOptions& options, std::size_t line);
double tool_path_u(const NurbsSurface& surface, const ToolPathOptions& options, std::size_t k);

// Line `line` (0-based, < options.lines) of the tool path on `surface`.
// Throws Error where a normal is undefined or horizontal.
ToolPathLine plan_line(const NurbsSurface& surface, const ToolPathOptions& options,
                       std::size_t line);

}  // namespace cnclab
