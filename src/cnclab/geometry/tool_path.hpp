#pragma once
// Iso-parametric ball-end tool paths (patent 003 step 1, seed 000 "Sample
// construction"): N lines at a constant parameter, M cutter-contact (CC)
// points per line equally spaced in the other (the feed) parameter; the
// cutter location (CL) is the ball centre CC + R n, n the unit normal on the
// side the tool works from (3-axis machining along the tool axis, +z).
//
// A real face is rarely machinable over its whole parameter rectangle, so a
// line is cut into segments (runs of consecutive CC points) where it
//   - leaves the face (its trimming loops, outer boundary and holes: a
//     FaceDomain), always;
//   - is not reachable from the tool axis: the normal on the tool side is
//     more than max_normal_angle from the axis, or points away from it;
//   - passes a degenerate point, where S_u x S_v vanishes relative to the
//     surface's scale (a sphere's pole, a collapsed edge): no normal there;
// the last two refused by default (ConfigError naming the face, the line and
// the CC point) or cut away like trims (`unreachable: clip`). A CC point
// where the tool radius exceeds the concave radius of curvature (the ball
// would gouge the surface) is refused by default, or kept and flagged
// (`gouge: allow`). Each check also runs at the middle of every pair of
// neighbouring CC points, so a pair straddling a cut is no segment.
//
// Normals are oriented once for the whole face, never point by point: see
// ToolSide. Step errors are computed only between CC points of one segment.
#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/geometry/nurbs_curve.hpp"
#include "cnclab/geometry/nurbs_surface.hpp"
#include "cnclab/geometry/step_error.hpp"

namespace cnclab {

// Which parameter the tool feeds along; lines run at a constant value of the other.
enum class FeedDirection { u, v };
// What to do with CC points that are unreachable or degenerate.
enum class UnreachablePolicy { refuse, clip };
// What to do where the tool radius exceeds a concave radius of curvature.
enum class GougePolicy { refuse, allow };
// The side of the surface the tool works from, decided once per face:
//   automatic: a face of a closed solid from outside its material (its
//              outward normal: the face's orientation respected); any other
//              face, or a YAML surface, from the side that faces the tool
//              axis over most of its projected area (the sign of the sum of
//              (S_u x S_v) . axis over the path's CC points on the face;
//              where both sides face it alike, within 1e-9 of the sum of
//              its sizes, the side of the face's own normal);
//   front:     the side of S_u x S_v (a CAD face: of its oriented normal);
//   back:      the other side.
enum class ToolSide { automatic, front, back };

struct ToolPathOptions {
  // N, lines at a constant parameter c_l = c_min + (c_max - c_min) l / (N - 1),
  // l = 0..N-1 (seed 000: 200 lines). >= 2.
  std::size_t lines = 200;
  // M, CC points per line at t_k = t_min + (t_max - t_min) k / (M - 1)
  // (seed 000: 100 CL points per line, so M - 1 = 99 segments). >= 2.
  std::size_t points_per_line = 100;
  // R, ball-end cutter radius [mm] (seed 000 "Sample construction": 5 mm). > 0.
  double tool_radius = 5.0;
  // The feed parameter t (seed 000: along u, lines at constant v).
  FeedDirection feed = FeedDirection::u;
  // The tool axis (3-axis machining: the tool points down it, working from
  // its + side); any non-zero length, normalised where used. Default +z.
  std::vector<double> tool_axis = {0.0, 0.0, 1.0};
  // Largest angle [deg] between the normal on the tool side and the tool
  // axis at a CC point: a steeper wall (or an overhang, > 90) is unreachable.
  // 85 deg (n . axis >= 0.087) keeps the ball's contact below its equator
  // with a margin for the shank; the papers are silent. In (0, 90].
  double max_normal_angle = 85.0;
  UnreachablePolicy unreachable = UnreachablePolicy::refuse;
  GougePolicy gouge = GougePolicy::refuse;
  ToolSide tool_side = ToolSide::automatic;

  // Throws OptionError naming the field, value and rule.
  void validate() const;
  Eigen::Vector3d unit_tool_axis() const;
};

// The face a path is planned on, beyond its NURBS form.
class FaceDomain {
 public:
  virtual ~FaceDomain() = default;
  // Whether S(u, v) of `surface` (the face's NURBS form) lies on the face:
  // inside its trimming loops or on them, to the face's tolerance.
  virtual bool contains(const NurbsSurface& surface, double u, double v) const = 0;
};

struct FaceContext {
  std::string label = "the surface";         // "face 3 of part.step", for messages
  std::shared_ptr<const FaceDomain> domain;  // null: the whole parameter rectangle
  // The face's own normal is orientation (S_u x S_v): -1 for a reversed CAD face.
  int orientation = 1;
  // Whether the face bounds a closed solid (its own normal then points out of the material).
  bool of_solid = false;
};

// Why a CC point is not on a segment (on_path: it is).
enum class PointState { on_path, outside_face, unreachable, degenerate };

// A segment of a line: CC points first..last (last > first), each pair of
// neighbours one step-error sample.
struct PathRun {
  std::size_t first = 0, last = 0;
};

// One tool-path line: its CC curve and the CC/CL points along it.
struct ToolPathLine {
  std::size_t index = 0;  // l
  FeedDirection feed = FeedDirection::u;
  double fixed = 0.0;                   // c_l, the line's constant parameter (v for a u feed)
  NurbsCurve curve;                     // exact CC curve t -> S along the feed
  std::vector<double> t;                // t_k, k = 0..M-1 (the feed parameter)
  std::vector<Eigen::Vector3d> cc;      // S at t_k [mm]
  std::vector<Eigen::Vector3d> normal;  // unit normal on the tool side (zero where undefined)
  std::vector<Eigen::Vector3d> cl;      // cc + R normal [mm]
  std::vector<PointState> state;        // per CC point
  std::vector<char> gouge;              // per pair i: 1 where R exceeds a concave radius (allowed)
  std::vector<PathRun> runs;            // the segments, in feed order
  double tool_radius = 0.0;             // R [mm]

  // (u, v) of parameter t on this line.
  Eigen::Vector2d uv(double t_value) const;
  // "line 3 (v = 0.25)", for messages.
  std::string label() const;
  // Pair i (CC points i and i + 1 of one run); refers to `curve`.
  StepErrorSegment segment(std::size_t i) const {
    return {&curve, t[i], t[i + 1], cl[i], cl[i + 1], tool_radius};
  }
};

// Sample s of a step-error dataset: pair (point, point + 1) of run `run` of line `line`.
struct PathSample {
  std::size_t line = 0, run = 0, point = 0;
};

// How many CC points of the path were cut, by reason.
struct PathCuts {
  std::size_t outside_face = 0, unreachable = 0, degenerate = 0;
  std::size_t gouge_allowed = 0;  // segments where the ball gouges, kept (gouge: allow)
};

struct ToolPath {
  std::vector<ToolPathLine> lines;
  std::vector<PathSample> samples;  // line by line, runs in feed order
  int side = 1;                     // +1: the tool on the side of S_u x S_v, -1: the other
  PathCuts cuts;
  std::size_t points() const;  // CC points of the whole grid, N x M
};

// Why plan_tool_path refused a path.
enum class Refusal { unreachable, degenerate, gouge, nothing_left };

// plan_tool_path's refusal: a ConfigError whose message names the face, the
// line, the CC point and the values; reason() for summaries.
class PathRefused : public ConfigError {
 public:
  PathRefused(const std::string& message, Refusal reason, int side)
      : ConfigError(message), reason_(reason), side_(side) {}
  Refusal reason() const { return reason_; }
  int side() const { return side_; }  // ToolPath::side, decided before the refusal

 private:
  Refusal reason_;
  int side_;
};

// "unreachable", "degenerate", "gouge", "nothing left on the face".
const char* refusal_name(Refusal reason);

// The parameters of line l and of CC point k (formulas at ToolPathOptions;
// the last value is the range end exactly).
double tool_path_fixed(const NurbsSurface& surface, const ToolPathOptions& options,
                       std::size_t line);
double tool_path_t(const NurbsSurface& surface, const ToolPathOptions& options, std::size_t k);

// The tool path on `surface` (options valid). PathRefused naming
// face.label, the line and the CC point for a refused point (see the top of
// this file) and for a path with no segment left; ResourceError for memory
// beyond the budget.
ToolPath plan_tool_path(const NurbsSurface& surface, const ToolPathOptions& options,
                        const FaceContext& face = {});

}  // namespace cnclab
