#pragma once
// Trochoidal tool path for a straight groove (seed 004 Sec. 3, Eq. 6, Table 2).
//
// Eq. 6: x = V t + R cos(w t),  y = R sin(w t): a point circling at radius R
// with angular rate w while the circle's centre moves at speed V along x.
// For a groove of width W cut with a cutter of diameter D (the tool CENTRE
// follows the trochoid):
//   R = (W - D) / 2                     (the loop's outer edge touches the walls)
//   centre travel  L_c = L - W          (the end loops' tools touch the groove ends)
//   loops          N = ceil(L_c / step) (step = advance per loop, Table 2 "Step")
//   advance        p = L_c / N <= step  (rounded down: a whole number of loops, no gouge)
//   w = 1 rad per unit t                (t is the loop angle), V = p / (2 pi)
// The path: one full circle about the start centre (the groove's start
// semicircle is reached only with the centre at x = W/2), the N loops of
// Eq. 6, one full circle about the end centre (likewise) - parameter
// t in [0, 2 pi (N + 2)], the centre at W/2 + V clamp(t - 2 pi, 0, 2 pi N). Sampling: equal steps
// dt in t with the chord deviation of each G01 segment from the curve at most `chord_tolerance`:
// the curve's smallest radius of curvature is R - V (at the inner side of a
// loop, for V < R), and a chord of angle a on a circle of radius rho deviates
// by rho (1 - cos(a / 2)), so dt = 2 acos(1 - tol / (R + V)) bounds it using
// the largest radius R + V (conservative), rounded to a whole number of
// samples per loop.
//
// Frame: x along the groove from its start (x = 0) to x = L, y = 0 on the
// groove's centreline; the loop starts at angle 0 (x = W/2 + R, y = 0) and runs
// counter-clockwise (climb milling on the advancing side for a clockwise
// spindle).
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace cnclab {

struct TrochoidGrooveOptions {
  double cutter_diameter = 20.0;   // D [mm] (Table 2)
  double groove_width = 28.0;      // W [mm] (Table 2)
  double groove_length = 120.0;    // L [mm] (Table 2)
  double step = 1.5;               // largest advance per loop [mm] (Table 2 "Step", Fig. 5)
  double chord_tolerance = 0.005;  // largest deviation of a G01 chord from Eq. 6 [mm]

  // D > 0; D < W (the loop radius R = (W - D)/2 must be > 0: a cutter as wide
  // as the groove is plain slotting, wider cannot cut it); L >= W (room for one
  // loop); 0 < step <= 2R (wider steps leave material between loops); 0 <
  // chord_tolerance < R; all finite.
  void validate() const;
};

struct TrochoidGroove {
  TrochoidGrooveOptions options;
  double radius = 0;         // R [mm]
  double centre_start = 0;   // x of the loop centre at t = 0 [mm]
  double centre_travel = 0;  // L - W [mm]
  std::size_t loops = 0;     // N
  double advance = 0;        // p = travel / N [mm per loop]
  double speed = 0;          // V = p / (2 pi) [mm per unit t]
  std::size_t samples_per_loop = 0;
  double dt = 0;  // parameter step [rad]
  // Sample points along the path (tool centre), with their parameter t:
  // start circle, N loops of Eq. 6, end circle.
  std::vector<double> t;
  std::vector<Eigen::Vector2d> points;
};

// Eq. 6 at parameter t for radius R and speed V (w = 1), before the
// groove's offset: (V t + R cos t, R sin t).
Eigen::Vector2d trochoid_point(double radius, double speed, double t);

TrochoidGroove make_trochoid_groove(const TrochoidGrooveOptions& options);

}  // namespace cnclab
