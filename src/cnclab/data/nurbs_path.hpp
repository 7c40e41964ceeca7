#pragma once
// A planar NURBS curve (geometry module) as a motion::PlanarPath, and seed
// 002's random NURBS tool path ("a randomly generated NURBS toolpath",
// Sec. II, Fig. 4). Lives in data because geometry and motion are siblings
// under core (docs/architecture.md: core <- geometry <- data, core <- motion <- data).
#include <cstddef>

#include "cnclab/core/rng.hpp"
#include "cnclab/geometry/nurbs_curve.hpp"
#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

// u_begin/u_end = the clamped knot range; evaluate = x, y of the curve point
// and its first three derivatives (geometry's curve_derivatives: A3.2 on the
// homogeneous curve + rational quotient rule).
class NurbsPlanarPath final : public PlanarPath {
 public:
  // Throws OptionError when the curve is invalid or a control point has
  // z != 0 (the path must lie in the xy plane).
  explicit NurbsPlanarPath(NurbsCurve curve);
  double u_begin() const override { return curve_.first(); }
  double u_end() const override { return curve_.last(); }
  PathPoint evaluate(double u) const override;
  const NurbsCurve& curve() const { return curve_; }

 private:
  NurbsCurve curve_;
};

struct RandomNurbsPathOptions {
  // Curve degree p. Default 4: the lowest degree whose C''' is continuous at
  // simple knots (C^(p-1)), so the planner's jerk limit, imposed at grid
  // nodes, also holds between them; seed 002 does not state its degree.
  int degree = 4;
  // Number of control points (>= degree + 1). Seed 002 is silent.
  std::size_t control_points = 100;
  // Work area [mm] holding every control point (seed 002's router is not
  // specified; 400 x 400 mm).
  double x_min = 0.0, x_max = 400.0;
  double y_min = 0.0, y_max = 400.0;
  // Control points form a random walk: the first uniform in the work area
  // with a uniform heading; each next one a step of length uniform in
  // [step_min, step_max] [mm] after turning the heading by a uniform angle in
  // [-max_turn, max_turn] [deg], redrawn (up to 32 times) while it would
  // leave the area; a walker still cornered heads for the area's centre
  // (turn unbounded there, left to the curvature check). Why a walk and not
  // points uniform in the area: uniform points make a tight loop almost
  // every few points (radius < 1 mm at 8 points in 100 x 80 mm), which no
  // 1 mm planning grid resolves and a real tool path would not contain.
  // step_max <= half the smaller side of the area.
  double step_min = 20.0, step_max = 60.0;
  double max_turn = 60.0;
  // Weights uniform in [weight_min, weight_max] (> 0); both 1 gives a
  // polynomial B-spline.
  double weight_min = 1.0, weight_max = 1.0;
  // Cusp check (motion's check_regular_path) applied to the drawn curve.
  RegularityOptions regularity;
  // Smallest radius of curvature 1/kappa allowed anywhere on the curve [mm],
  // kappa = |x'y'' - y'x''| / |C'|^3 (seed 002 Eq. 5), checked on the
  // regularity.samples grid. Random control points can make a turn of almost
  // zero radius without a cusp; the planner imposes the limits at grid nodes
  // 1 mm apart and cannot resolve it (measured: a 0.22 mm turn exceeded the
  // acceleration limit by 16 % between nodes). >= 0; 0 = no check.
  double min_curvature_radius = 5.0;
  // Curves drawn from the stream until one passes both checks (>= 1).
  int max_attempts = 100;

  void validate() const;  // OptionError naming the field
};

// Control points and weights drawn from `rng` (the walk, then the weights
// when weight_min < weight_max); clamped knot vector on
// [0, 1] with uniform interior knots. The same stream state gives the same
// curve. A curve failing the cusp or curvature check is discarded and the
// next one drawn, up to max_attempts. Throws OptionError for bad options, and
// cnclab::Error ("random NURBS path (...): no curve of N attempts passed; last:
// path has a cusp ... at u = ..." or "... radius of curvature ... at u = ...").
NurbsCurve random_planar_nurbs(const RandomNurbsPathOptions& options, Rng& rng);

}  // namespace cnclab
