#pragma once
// Closed-form planar paths with exact derivatives: test cases with known
// answers (line, circle) and smooth long paths for benchmarks, until NURBS
// paths from the geometry module are adapted to PlanarPath.
#include <array>

#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

// C(u) = start + u (end - start), u in [0, 1].
class LinePath final : public PlanarPath {
 public:
  LinePath(const Vec2& start, const Vec2& end);
  double u_begin() const override { return 0.0; }
  double u_end() const override { return 1.0; }
  PathPoint evaluate(double u) const override;

 private:
  Vec2 start_, delta_;
};

// C(u) = centre + r (cos u, sin u), u in [angle_begin, angle_end] (radians;
// angle_end < angle_begin runs clockwise).
class CirclePath final : public PlanarPath {
 public:
  CirclePath(const Vec2& centre, double radius, double angle_begin, double angle_end);
  double u_begin() const override { return 0.0; }
  double u_end() const override { return 1.0; }
  PathPoint evaluate(double u) const override;
  const Vec2& centre() const { return centre_; }
  double radius() const { return radius_; }

 private:
  Vec2 centre_;
  double radius_, angle_begin_, sweep_;
};

// Cubic Bezier curve, u in [0, 1] (Bernstein form; C''' is constant).
class CubicBezierPath final : public PlanarPath {
 public:
  explicit CubicBezierPath(const std::array<Vec2, 4>& control_points);
  double u_begin() const override { return 0.0; }
  double u_end() const override { return 1.0; }
  PathPoint evaluate(double u) const override;

 private:
  std::array<Vec2, 4> p_;
};

// Epitrochoid-like curve C(u) = centre + R1 (cos u, sin u) + R2 (cos ku, sin ku),
// u in [0, 2 pi turns]. |C'(u)|^2 = R1^2 + k^2 R2^2 + 2 k R1 R2 cos((k-1)u)
// >= (R1 - k R2)^2, so it has no cusp when R1 != k R2: a long, smooth path with
// curvature changing sign along it.
class EpitrochoidPath final : public PlanarPath {
 public:
  EpitrochoidPath(const Vec2& centre, double r1, double r2, double k, double turns);
  double u_begin() const override { return 0.0; }
  double u_end() const override { return u_end_; }
  PathPoint evaluate(double u) const override;

 private:
  Vec2 centre_;
  double r1_, r2_, k_, u_end_;
};

}  // namespace cnclab
