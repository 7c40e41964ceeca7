// plan_tool_path (tool_path.hpp): the grid of CC points, cut where it leaves
// the face or cannot be machined, refused where the options say so.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/geometry/surface_curvature.hpp"
#include "cnclab/geometry/tool_path.hpp"

namespace cnclab {
namespace {

// A point is degenerate where |S_u x S_v| < kDegenerateFraction * scale, the
// scale (diagonal of the control net's box)^2 / (u range * v range): about
// |S_u| |S_v| of the surface, so the test does not depend on where the point
// is or how dense the path is. On a sphere of radius rho that is within
// ~1e-7 rho of a pole (S_u there is rounding noise, its direction random);
// further out rounding (1e-16 of the coordinates) turns the normal by less
// than 1e-8 rad, 5e-5 um of CL position at R = 5 mm.
constexpr double kDegenerateFraction = 1e-7;
// R kappa above 1 by more than rounding is a gouge: a ball exactly fitting a
// fillet (R = 1 / kappa) touches it along a line and cuts nothing.
constexpr double kGougeSlack = 1e-9;
constexpr double kDeg = std::numbers::pi / 180.0;

std::string num(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

std::string vector_text(const Eigen::Vector3d& p) {
  return std::string("(")
             .append(num(p.x()))
             .append(", ")
             .append(num(p.y()))
             .append(", ")
             .append(num(p.z())) +
         ")";
}

double derivative_scale(const NurbsSurface& s) {
  Eigen::Vector3d lo = s.points.front(), hi = lo;
  for (const Eigen::Vector3d& p : s.points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double du = s.knots_u.back() - s.knots_u.front();
  const double dv = s.knots_v.back() - s.knots_v.front();
  return (hi - lo).squaredNorm() / (du * dv);
}

// A concave radius of curvature 1/kappa, or what the surface is there
// (curvatures below 1e-9 / R are rounding on a flat direction).
std::string radius_text(double kappa, double tool_radius) {
  return kappa * tool_radius > 1e-9 ? num(1.0 / kappa) + " mm" : "none (convex or flat)";
}

struct Verdict {
  PointState state = PointState::on_path;
  bool gouge = false;
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();  // on the tool side
  std::string why;                                   // state or gouge, for a refusal
};

class Planner {
 public:
  Planner(const NurbsSurface& s, const ToolPathOptions& o, const FaceContext& f)
      : s_(s),
        o_(o),
        f_(f),
        axis_(o.unit_tool_axis()),
        cos_max_(std::cos(o.max_normal_angle * kDeg)),
        degenerate_below_(kDegenerateFraction * derivative_scale(s)) {}

  ToolPath plan() {
    const std::size_t n = o_.lines, m = o_.points_per_line;
    check_memory(
        static_cast<double>(n) * static_cast<double>(m) * 96.0,
        "tool path (" + std::to_string(n) + " lines x " + std::to_string(m) + " CC points)");
    ToolPath path;
    path.lines.resize(n);
    // Sums of (S_u x S_v) . axis and of its size over the CC points on the face.
    Facing facing;
    for (std::size_t l = 0; l < n; ++l) lay_out(path.lines[l], l, facing);
    side_ = decide_side(facing);
    path.side = side_;
    for (ToolPathLine& line : path.lines) {
      check_line(line, path.cuts);
      for (std::size_t r = 0; r < line.runs.size(); ++r) {
        for (std::size_t i = line.runs[r].first; i < line.runs[r].last; ++i) {
          path.samples.push_back({line.index, r, i});
          path.cuts.gouge_allowed += line.gouge[i];
        }
      }
    }
    if (path.samples.empty()) {
      throw PathRefused(
          f_.label + ": no segment of the tool path is left on the face (of " +
              std::to_string(n * m) + " CC points " + std::to_string(path.cuts.outside_face) +
              " lie outside the face, " + std::to_string(path.cuts.unreachable) +
              " are unreachable from the tool axis " + vector_text(axis_) + ", " +
              std::to_string(path.cuts.degenerate) +
              " degenerate; no two neighbours of the rest lie on the face with their "
              "middle); try more lines or points_per_line, another feed, tool_axis or face",
          Refusal::nothing_left, side_);
    }
    return path;
  }

 private:
  struct Facing {
    double sum = 0.0, size = 0.0;
  };

  // Line l's curve and CC points, which lie on the face; adds the line's
  // share of the facing sums.
  void lay_out(ToolPathLine& line, std::size_t l, Facing& facing) const {
    const std::size_t m = o_.points_per_line;
    line.index = l;
    line.feed = o_.feed;
    line.fixed = tool_path_fixed(s_, o_, l);
    line.curve =
        o_.feed == FeedDirection::u ? iso_curve_u(s_, line.fixed) : iso_curve_v(s_, line.fixed);
    line.tool_radius = o_.tool_radius;
    line.t.resize(m);
    line.cc.resize(m);
    line.normal.assign(m, Eigen::Vector3d::Zero());
    line.cl.resize(m);
    line.state.assign(m, PointState::on_path);
    line.gouge.assign(m - 1, 0);
    for (std::size_t k = 0; k < m; ++k) {
      line.t[k] = tool_path_t(s_, o_, k);
      const Eigen::Vector2d uv = line.uv(line.t[k]);
      const SurfaceDerivatives d = surface_derivatives(s_, uv.x(), uv.y());
      line.cc[k] = d.point;
      line.cl[k] = d.point;
      if (!on_face(uv)) {
        line.state[k] = PointState::outside_face;
        continue;
      }
      const double along = d.du.cross(d.dv).dot(axis_);
      facing.sum += along;
      facing.size += std::abs(along);
    }
  }

  bool on_face(const Eigen::Vector2d& uv) const {
    return !f_.domain || f_.domain->contains(s_, uv.x(), uv.y());
  }

  // A free face whose two sides face the tool alike (a whole cylinder
  // about a horizontal axis: the sum is rounding) is machined from its own
  // normal's side, as `front`.
  int decide_side(const Facing& facing) const {
    switch (o_.tool_side) {
      case ToolSide::front:
        return f_.orientation;
      case ToolSide::back:
        return -f_.orientation;
      case ToolSide::automatic:
        break;
    }
    if (f_.of_solid || std::abs(facing.sum) <= 1e-9 * facing.size) return f_.orientation;
    return facing.sum > 0.0 ? 1 : -1;
  }

  Verdict judge(const SurfaceDerivatives& d) const {
    Verdict v;
    const Eigen::Vector3d raw = d.du.cross(d.dv);
    const double length = raw.norm();
    if (!(length > degenerate_below_)) {
      v.state = PointState::degenerate;
      v.why = "S_u x S_v vanishes there (|S_u x S_v| = " + num(length) + ", " +
              num(length / (degenerate_below_ / kDegenerateFraction)) +
              " of the surface's scale: a pole or a collapsed edge), so it has no normal";
      return v;
    }
    v.normal = side_ * raw / length;
    const double c = v.normal.dot(axis_);
    if (c < cos_max_) {
      v.state = PointState::unreachable;
      v.why = "the normal on the tool side " + vector_text(v.normal) + " is " +
              num(std::acos(std::clamp(c, -1.0, 1.0)) / kDeg) + " deg from the tool axis " +
              vector_text(axis_) + ", beyond max_normal_angle = " + num(o_.max_normal_angle) +
              " deg" +
              (c > -1e-9 ? " (a wall too steep for the tool)"
               : f_.of_solid && o_.tool_side == ToolSide::automatic
                   ? " (the face's outward normal points away from the tool: its material is "
                     "in the way)"
                   : " (the surface faces away from the tool there)");
      return v;
    }
    const SurfaceCurvatures k =
        surface_curvatures(d, v.normal, o_.feed == FeedDirection::u ? d.du : d.dv);
    if (o_.tool_radius * k.max > 1.0 + kGougeSlack) {
      v.gouge = true;
      v.why = "the tool radius R = " + num(o_.tool_radius) +
              " mm exceeds the surface's smallest concave radius of curvature " +
              radius_text(k.max, o_.tool_radius) + " there (along the feed " +
              radius_text(k.along, o_.tool_radius) + ", across it " +
              radius_text(k.across, o_.tool_radius) + "): the ball would cut into the surface";
    }
    return v;
  }

  // Refuses (throws) unless the options cut or keep such points; true when
  // the point stays on the path.
  bool accept(const Verdict& v, const ToolPathLine& line, const std::string& where,
              const Eigen::Vector3d& p) const {
    const bool unreachable = v.state != PointState::on_path;
    if (unreachable && o_.unreachable == UnreachablePolicy::clip) return false;
    if (!unreachable && (!v.gouge || o_.gouge == GougePolicy::allow)) return true;
    const std::string hint =
        unreachable ? "; `unreachable: clip` cuts such points from the path" +
                          std::string(v.state == PointState::unreachable
                                          ? " (tool_axis and max_normal_angle set the reach)"
                                          : "")
                    : "; use a smaller tool_radius, or `gouge: allow` to keep such points "
                      "(flagged in the dataset's `gouge` column)";
    throw PathRefused(f_.label + ": " + line.label() + ", " + where + " at " + vector_text(p) +
                          " mm: " + v.why + hint,
                      !unreachable                        ? Refusal::gouge
                      : v.state == PointState::degenerate ? Refusal::degenerate
                                                          : Refusal::unreachable,
                      side_);
  }

  void check_line(ToolPathLine& line, PathCuts& cuts) const {
    const std::size_t m = line.t.size();
    for (std::size_t k = 0; k < m; ++k) {
      if (line.state[k] == PointState::outside_face) {
        ++cuts.outside_face;
        continue;
      }
      const Eigen::Vector2d uv = line.uv(line.t[k]);
      const Verdict v = judge(surface_derivatives(s_, uv.x(), uv.y()));
      if (!accept(v, line, "CC point " + std::to_string(k), line.cc[k])) {
        line.state[k] = v.state;
        ++(v.state == PointState::degenerate ? cuts.degenerate : cuts.unreachable);
        continue;
      }
      line.normal[k] = v.normal;
      line.cl[k] = line.cc[k] + o_.tool_radius * v.normal;
      if (v.gouge) {
        if (k > 0) line.gouge[k - 1] = 1;
        if (k + 1 < m) line.gouge[k] = 1;
      }
    }
    // Pairs: both ends on the path and the middle on the face and machinable.
    std::size_t i = 0;
    while (i + 1 < m) {
      if (!pair_on_path(line, i)) {
        ++i;
        continue;
      }
      PathRun run{i, i + 1};
      while (run.last + 1 < m && pair_on_path(line, run.last)) ++run.last;
      line.runs.push_back(run);
      i = run.last + 1;  // pair run.last is off the path (or the line ends)
    }
  }

  bool pair_on_path(ToolPathLine& line, std::size_t i) const {
    if (line.state[i] != PointState::on_path || line.state[i + 1] != PointState::on_path) {
      return false;
    }
    const Eigen::Vector2d uv = line.uv(0.5 * (line.t[i] + line.t[i + 1]));
    if (!on_face(uv)) return false;
    const SurfaceDerivatives d = surface_derivatives(s_, uv.x(), uv.y());
    const Verdict v = judge(d);
    if (!accept(v, line, "between CC points " + std::to_string(i) + " and " + std::to_string(i + 1),
                d.point)) {
      return false;
    }
    if (v.gouge) line.gouge[i] = 1;
    return true;
  }

  const NurbsSurface& s_;
  const ToolPathOptions& o_;
  const FaceContext& f_;
  Eigen::Vector3d axis_;
  double cos_max_;
  double degenerate_below_;
  int side_ = 1;
};

}  // namespace

const char* refusal_name(Refusal reason) {
  switch (reason) {
    case Refusal::unreachable:
      return "unreachable";
    case Refusal::degenerate:
      return "degenerate";
    case Refusal::gouge:
      return "gouge";
    case Refusal::nothing_left:
      break;
  }
  return "nothing left on the face";
}

ToolPath plan_tool_path(const NurbsSurface& surface, const ToolPathOptions& options,
                        const FaceContext& face) {
  return Planner(surface, options, face).plan();
}

}  // namespace cnclab
