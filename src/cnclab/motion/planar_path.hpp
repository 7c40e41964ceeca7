#pragma once
// A planar tool path C(u) = (x(u), y(u)) in mm over a parameter interval
// [u_begin, u_end], with analytic derivatives up to the third. Everything in
// the motion module (feedrate planning, interpolation, contour error) works
// on this interface; a NURBS curve from the geometry module plugs in through
// an adapter that implements it (derivatives from The NURBS Book A3.2/A4.2).
#include <Eigen/Core>
#include <string>

namespace cnclab {

using Vec2 = Eigen::Vector2d;

// C(u) and its derivatives with respect to u: mm, mm/u, mm/u^2, mm/u^3.
struct PathPoint {
  Vec2 position = Vec2::Zero();
  Vec2 d1 = Vec2::Zero();
  Vec2 d2 = Vec2::Zero();
  Vec2 d3 = Vec2::Zero();
};

class PlanarPath {
 public:
  virtual ~PlanarPath() = default;
  virtual double u_begin() const = 0;
  virtual double u_end() const = 0;
  // C and its first three derivatives at u in [u_begin, u_end]. C' and C''
  // must be continuous; C''' should be (the planner bounds the jerk, which
  // contains C''', at grid nodes only; a jump between nodes, as at a cubic
  // spline's knots, is not seen there).
  virtual PathPoint evaluate(double u) const = 0;
};

// Arc length of the path by composite 5-point Gauss-Legendre quadrature over
// `intervals` equal parameter intervals.
double arc_length(const PlanarPath& path, int intervals = 2048);
// Arc length between two parameters (u0 <= u1), same rule.
double arc_length(const PlanarPath& path, double u0, double u1, int intervals);

// The part of a path between two of its parameters: the same C(u) over
// [u0, u1], u_begin <= u0 < u1 <= u_end (the path must outlive it). A
// section planned on its own starts and ends at rest.
class PathPiece final : public PlanarPath {
 public:
  PathPiece(const PlanarPath& path, double u0, double u1) : path_(&path), u0_(u0), u1_(u1) {}
  double u_begin() const override { return u0_; }
  double u_end() const override { return u1_; }
  PathPoint evaluate(double u) const override { return path_->evaluate(u); }

 private:
  const PlanarPath* path_;
  double u0_, u1_;
};

// The parameter at arc length s from u_begin (clamped to the path), by 60
// bisection steps on arc_length(path, u_begin, u, 256).
double parameter_at_arc_length(const PlanarPath& path, double s);

struct RegularityOptions {
  // Parameter samples checked (uniform in u, both ends included).
  int samples = 20001;
  // |C'(u)| must stay >= min_speed_ratio * (arc length / parameter range),
  // i.e. a fraction of the mean parametric speed. A cusp or a stationary
  // point (C'(u) = 0) makes the tangent undefined and the feedrate
  // problem singular (axis velocity = C'(u) du/dt).
  double min_speed_ratio = 1e-3;

  void validate() const;
};

// Throws cnclab::Error naming the parameter and the speed when |C'(u)| comes
// closer to 0 than the rule above (a cusp), or the range is empty/not finite.
void check_regular_path(const PlanarPath& path, const RegularityOptions& options = {});

}  // namespace cnclab
