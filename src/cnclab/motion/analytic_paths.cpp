#include "cnclab/motion/analytic_paths.hpp"

#include <cmath>
#include <numbers>

namespace cnclab {

LinePath::LinePath(const Vec2& start, const Vec2& end) : start_(start), delta_(end - start) {}

PathPoint LinePath::evaluate(double u) const {
  PathPoint p;
  p.position = start_ + u * delta_;
  p.d1 = delta_;
  return p;
}

CirclePath::CirclePath(const Vec2& centre, double radius, double angle_begin, double angle_end)
    : centre_(centre),
      radius_(radius),
      angle_begin_(angle_begin),
      sweep_(angle_end - angle_begin) {}

PathPoint CirclePath::evaluate(double u) const {
  // theta = angle_begin + sweep u; each u-derivative brings a factor sweep.
  const double theta = angle_begin_ + sweep_ * u;
  const Vec2 radial(std::cos(theta), std::sin(theta));
  const Vec2 tangential(-std::sin(theta), std::cos(theta));
  const double s = sweep_;
  PathPoint p;
  p.position = centre_ + radius_ * radial;
  p.d1 = radius_ * s * tangential;
  p.d2 = -radius_ * s * s * radial;
  p.d3 = -radius_ * s * s * s * tangential;
  return p;
}

CubicBezierPath::CubicBezierPath(const std::array<Vec2, 4>& control_points) : p_(control_points) {}

PathPoint CubicBezierPath::evaluate(double u) const {
  const double v = 1.0 - u;
  PathPoint p;
  p.position =
      v * v * v * p_[0] + 3 * v * v * u * p_[1] + 3 * v * u * u * p_[2] + u * u * u * p_[3];
  // Derivatives of a Bezier curve are Bezier curves of the forward differences.
  const Vec2 d0 = p_[1] - p_[0], d1 = p_[2] - p_[1], d2 = p_[3] - p_[2];
  p.d1 = 3 * (v * v * d0 + 2 * v * u * d1 + u * u * d2);
  p.d2 = 6 * (v * (d1 - d0) + u * (d2 - d1));
  p.d3 = 6 * (d2 - 2 * d1 + d0);
  return p;
}

EpitrochoidPath::EpitrochoidPath(const Vec2& centre, double r1, double r2, double k, double turns)
    : centre_(centre), r1_(r1), r2_(r2), k_(k), u_end_(2 * std::numbers::pi * turns) {}

PathPoint EpitrochoidPath::evaluate(double u) const {
  const Vec2 a(std::cos(u), std::sin(u));
  const Vec2 at(-std::sin(u), std::cos(u));
  const Vec2 b(std::cos(k_ * u), std::sin(k_ * u));
  const Vec2 bt(-std::sin(k_ * u), std::cos(k_ * u));
  const double k = k_;
  PathPoint p;
  p.position = centre_ + r1_ * a + r2_ * b;
  p.d1 = r1_ * at + r2_ * k * bt;
  p.d2 = -r1_ * a - r2_ * k * k * b;
  p.d3 = -r1_ * at - r2_ * k * k * k * bt;
  return p;
}

}  // namespace cnclab
