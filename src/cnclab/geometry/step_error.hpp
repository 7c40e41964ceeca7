#pragma once
// Step error of a 3-axis ball-end tool path segment (seed 000 Eq. 1, Fig. 1).
//
// Between CL points P_i and P_i+1 the ball sweeps a cylinder of radius R
// around the CL line. L(u) is the distance from the CC-curve point C(u),
// u in [u_i, u_i+1], to that line:
//   L(u) = |(P_i+1 - P_i) x (C(u) - P_i)| / |P_i+1 - P_i|.
// Convex segment: p_e minimises L; concave: p_e maximises L; e_i = |R - L(p_e)|.
//
// Convexity is not defined by the paper; we classify a segment as convex when
// the CC curve bulges toward the tool, i.e. when its parameter midpoint is
// closer to the CL line than the midpoint of the chord CC_i CC_i+1 is. On a
// circle of radius rho this gives e = (rho + R)(1 - cos(theta/2)) outside and
// e = (rho - R)(1 - cos(theta/2)) inside (tests/geometry/step_error_test.cpp).
#include <Eigen/Core>

#include "cnclab/geometry/nurbs_curve.hpp"

namespace cnclab {

// One segment: the CC curve restricted to [u0, u1] and the two CL points.
struct StepErrorSegment {
  const NurbsCurve* curve = nullptr;  // the line's CC curve (not owned)
  double u0 = 0.0, u1 = 0.0;          // CC parameters u_i < u_i+1
  Eigen::Vector3d cl0, cl1;           // CL points P_i, P_i+1 [mm]
  double tool_radius = 5.0;           // R [mm]
};

struct StepError {
  double error = 0.0;      // e_i = |R - L(p_e)| [mm]
  double u_extreme = 0.0;  // parameter of p_e
  double distance = 0.0;   // L(p_e) [mm]
  bool convex = true;      // the classification above
  int evaluations = 0;     // CC-curve evaluations spent (cost measure)
};

struct ExactStepErrorOptions {
  // Intervals of the bracketing grid over [u_i, u_i+1]: the extreme grid
  // point brackets the extreme of L for any segment where L has at most one
  // extreme per 2 grid intervals. >= 2.
  int grid_intervals = 32;
  // Safeguarded Newton on dL^2/du stops when the step or the bracket is
  // below this, in u. > 0.
  double tolerance_u = 1e-12;
  int max_iterations = 100;  // Newton/bisection iterations, >= 1
  void validate() const;
};

// The theoretical value: bracket the extreme of L^2 on the grid, then
// safeguarded Newton (Newton with bisection fallback, Numerical Recipes
// rtsafe) on g(u) = d L^2/du using the exact C' and C'' of the NURBS curve.
// Throws Error if the CL points coincide.
StepError exact_step_error(const StepErrorSegment& segment,
                           const ExactStepErrorOptions& options = {});

struct IterativeStepErrorOptions {
  // Discrete points per pass, ends included (the paper's geometric methods
  // sample the CC curve, refs. 1-3 and 26 of seed 000). >= 3.
  int points_per_pass = 10;
  // Stop when the bracket around the extreme is below this fraction of the
  // segment's parameter length. > 0.
  double relative_tolerance = 1e-6;
  int max_passes = 100;  // >= 1
  void validate() const;
};

// The iterative geometric method the paper compares against: sample the CC
// curve at equally spaced points, take the extreme distance to the CL line,
// shrink the interval to the neighbours of the extreme point and repeat.
StepError iterative_step_error(const StepErrorSegment& segment,
                               const IterativeStepErrorOptions& options = {});

// L(u) for the segment (seed 000 Eq. 1).
double distance_to_cl_line(const StepErrorSegment& segment, double u);
// The convex/concave classification above.
bool is_convex_segment(const StepErrorSegment& segment);

}  // namespace cnclab
