#pragma once
// Contour error: the distance from the actual tool position P to the
// reference path (seed 002, Fig. 1), exactly by local projection and by the
// closed-form estimates that need only the interpolator's data at the
// reference point R = C(u_ref): the Taylor estimate of seed 002 Eqs. 3-6,
// the tangent line and the osculating circle.
#include <vector>

#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/planar_path.hpp"

namespace cnclab {

// Local geometry at a path point, seed 002 Eqs. 5-6 (planar: the cross
// products are taken with z = 0):
//   kappa = |C' x C''| / |C'|^3,  t = C'/|C'|,  b = C' x C'' / |C' x C''|,
//   n = (b x C') / |b x C'|      (n points to the centre of curvature).
// Where C' x C'' = 0 (kappa = 0) b is undefined; n is then the left normal,
// which no estimate uses with a nonzero weight.
struct PathFrame {
  Vec2 tangent = Vec2::UnitX();
  Vec2 normal = Vec2::UnitY();
  double curvature = 0.0;  // [1/mm]
};
PathFrame path_frame(const PathPoint& point);

struct ProjectionOptions {
  // Search window around u_ref, as arc length each side [mm]:
  // max(window_factor * |P - R|, min_window), growing x2 up to max_window
  // while the distance keeps falling at its edge. The window keeps the foot
  // on the branch of the path the reference is on (a path that returns close
  // to itself has other, far branches).
  double window_factor = 3.0;
  double min_window = 0.5;
  double max_window = 50.0;
  int samples = 32;          // bracketing samples of d/du |C(u) - P|^2 in the window
  double tolerance = 1e-12;  // on u, relative to the window width
  int max_iterations = 100;  // safeguarded Newton steps

  void validate() const;
};

struct Projection {
  double u = 0.0;  // parameter of the foot point
  Vec2 foot = Vec2::Zero();
  double distance = 0.0;  // |P - C(u)| [mm], the exact contour error
};

// Nearest point to P on the path's branch around u_ref: the bracket is the
// sign change (- to +) of g(u) = C'(u).(C(u) - P) nearest to u_ref among
// window samples (or the closer window/path end when g has none), then
// Newton on g (g' = |C'|^2 + C''.(C - P)) from u_ref, falling back to
// bisection whenever a step leaves the bracket (Numerical Recipes' rtsafe).
Projection project_to_path(const PlanarPath& path, const Vec2& actual, double u_ref,
                           const ProjectionOptions& options = {});

// Seed 002 Eqs. 3-4 with e = R - P the following error vector (reference
// minus actual, as Fig. 1 and controllers define it):
//   Eq. 4:  c = e - (e.t) t,  c^ = c / sqrt(|e|^2 - (e.t)^2).
//     Our copy prints the denominator as sqrt(|e|^2 - e.t), which mixes a
//     squared length with a length; the intended quantity is |c|, the norm
//     of the part of e normal to the path, which needs (e.t)^2.
//   Eq. 3:  eps_c = -c^.e - (1/2) kappa (c^.n) (t.e)^2 / (1 + kappa (c.n)).
//     The copy prints "1 - kappa (c^.n)" with the unit vector; kappa has
//     units 1/mm, so the dimensionally consistent reading uses the normal
//     vector c itself. Its sign: with P = R + a t + b n (b > 0 towards the
//     centre of curvature) the distance from P to the osculating circle is
//     |b| - sign(b) kappa a^2 / (2 (1 - kappa b)) + O(a^4), and with c from
//     e = R - P, c.n = -b, so the denominator is 1 + kappa (c.n). The printed
//     minus holds for c taken from the opposite vector P - R; with c from
//     R - P it would give 1 + kappa b, the osculating circle's expansion about
//     the wrong centre distance, off by kappa^2 a^2 |b| (1.0e-5 mm on a circle
//     of r = 10 mm at a = b = 0.1 mm, against 1.3e-8 mm with this sign;
//     tests/motion/contour_error_test.cpp checks both sides of circles and
//     ellipses against closed forms). The fraction applies to the curvature
//     term only: over both terms it would add a kappa |c|^2 term that the
//     exact distance does not have.
// On a circle of radius r the exact distance is |sqrt(a^2 + (r - b)^2) - r|
// = |b| - sign(b) a^2 / (2 (r - b)) + a^4 / (8 |r - b|^3) - ...; this
// estimate is the series without the a^4 term: exact to third order, error
// <= a^4 / (8 |r - b|^3). On other curves the curvature's change along the
// path adds an O(|e|^3) error (fourth order again at the vertices of an
// ellipse, where d kappa / ds = 0).
// When c = 0 (P on the tangent line) c^ is taken as n. Returns eps_c
// (negative: the paper's vector points from the path to P opposite to c^);
// its magnitude is the contour error estimate.
double taylor_contour_error(const PathPoint& reference, const Vec2& actual);

// Distance from P to the tangent line at R: |e - (e.t) t| (first order).
double tangent_line_contour_error(const PathPoint& reference, const Vec2& actual);

// Distance from P to the osculating circle at R (centre R + n / kappa,
// radius 1 / kappa); the tangent-line value where kappa = 0. Exact on circles.
double osculating_circle_contour_error(const PathPoint& reference, const Vec2& actual);

// Exact contour error along a run and the three estimates' discrepancies
// from it (seed 002's comparison of estimation methods), over the samples of
// `reference` (1 ms) and the matching rows of `actual` (tool positions, mm).
struct EstimateDiscrepancy {
  double mean = 0.0;  // mean |estimate - exact| [mm]
  double max = 0.0;   // max |estimate - exact| [mm]
};
struct ContourErrorComparison {
  std::vector<double> exact;  // per sample [mm]
  EstimateDiscrepancy taylor, tangent_line, osculating_circle;
};
ContourErrorComparison compare_contour_estimates(const PlanarPath& path,
                                                 const ReferenceTrajectory& reference,
                                                 const Eigen::MatrixX2d& actual,
                                                 const ProjectionOptions& options = {});

}  // namespace cnclab
