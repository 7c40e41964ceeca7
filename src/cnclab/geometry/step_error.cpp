#include "cnclab/geometry/step_error.hpp"

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

void ExactStepErrorOptions::validate() const {
  if (grid_intervals < 2 || grid_intervals > 1'000'000) {
    throw OptionError("grid_intervals", std::to_string(grid_intervals), "must be in [2, 1000000]");
  }
  if (!(tolerance_u > 0.0) || !std::isfinite(tolerance_u)) {
    throw OptionError("tolerance_u", shortest_double(tolerance_u), "must be finite and > 0");
  }
  if (max_iterations < 1) {
    throw OptionError("max_iterations", std::to_string(max_iterations), "must be >= 1");
  }
}

void IterativeStepErrorOptions::validate() const {
  if (points_per_pass < 3) {
    throw OptionError("points_per_pass", std::to_string(points_per_pass), "must be >= 3");
  }
  if (!(relative_tolerance > 0.0) || !std::isfinite(relative_tolerance)) {
    throw OptionError("relative_tolerance", shortest_double(relative_tolerance),
                      "must be finite and > 0");
  }
  if (max_passes < 1) throw OptionError("max_passes", std::to_string(max_passes), "must be >= 1");
}

namespace {

// The CL line as origin + unit direction.
struct Line {
  Eigen::Vector3d origin, direction;
};

Line cl_line(const StepErrorSegment& s) {
  const Eigen::Vector3d axis = s.cl1 - s.cl0;
  const double length = axis.norm();
  if (!(length > 0.0)) {
    throw Error("step error: CL points coincide at (" + shortest_double(s.cl0.x()) + ", " +
                shortest_double(s.cl0.y()) + ", " + shortest_double(s.cl0.z()) +
                "); the CL line is undefined");
  }
  return {s.cl0, axis / length};
}

double squared_distance(const Line& line, const Eigen::Vector3d& p) {
  const Eigen::Vector3d d = p - line.origin;
  const double along = d.dot(line.direction);
  return std::max(0.0, d.squaredNorm() - along * along);
}

bool convex_against(const StepErrorSegment& s, const Line& line) {
  const Eigen::Vector3d cc0 = curve_point(*s.curve, s.u0), cc1 = curve_point(*s.curve, s.u1);
  const Eigen::Vector3d mid = curve_point(*s.curve, 0.5 * (s.u0 + s.u1));
  return squared_distance(line, mid) < squared_distance(line, 0.5 * (cc0 + cc1));
}

StepError finish(const StepErrorSegment& s, double u, double f, bool convex, int evaluations) {
  StepError e;
  e.u_extreme = u;
  e.distance = std::sqrt(f);
  e.error = std::abs(s.tool_radius - e.distance);
  e.convex = convex;
  e.evaluations = evaluations;
  return e;
}

}  // namespace

double distance_to_cl_line(const StepErrorSegment& s, double u) {
  return std::sqrt(squared_distance(cl_line(s), curve_point(*s.curve, u)));
}

bool is_convex_segment(const StepErrorSegment& s) {
  return convex_against(s, cl_line(s));
}

StepError exact_step_error(const StepErrorSegment& s, const ExactStepErrorOptions& o) {
  o.validate();
  const Line line = cl_line(s);
  const bool convex = convex_against(s, line);
  // Minimise sense * L^2: +1 for the minimum (convex), -1 for the maximum.
  const double sense = convex ? 1.0 : -1.0;
  const int n = o.grid_intervals;
  const double h = (s.u1 - s.u0) / n;
  const auto grid_u = [&](int k) { return k == n ? s.u1 : s.u0 + h * k; };
  int best = 0;
  double best_f = 0.0;
  for (int k = 0; k <= n; ++k) {
    const double f = squared_distance(line, curve_point(*s.curve, grid_u(k)));
    if (k == 0 || sense * f < sense * best_f) {
      best = k;
      best_f = f;
    }
  }
  int evaluations = n + 4;  // grid + the classification's three points
  // g(u) = sense * d(L^2)/du and its derivative from C, C', C''.
  struct Slope {
    double g, dg, f;
  };
  const auto slope = [&](double u) {
    const CurveDerivatives c = curve_derivatives(*s.curve, u);
    ++evaluations;
    const Eigen::Vector3d d = c.point - line.origin;
    const double da = d.dot(line.direction), c1a = c.d1.dot(line.direction);
    const double g = 2.0 * (d.dot(c.d1) - da * c1a);
    const double dg =
        2.0 * (c.d1.squaredNorm() + d.dot(c.d2) - c1a * c1a - da * c.d2.dot(line.direction));
    return Slope{sense * g, sense * dg, std::max(0.0, d.squaredNorm() - da * da)};
  };
  double lo = grid_u(std::max(best - 1, 0)), hi = grid_u(std::min(best + 1, n));
  const Slope at_lo = slope(lo), at_hi = slope(hi);
  // An extreme inside [lo, hi] needs g(lo) < 0 < g(hi); otherwise the grid
  // extreme is a segment end where L keeps falling (rising) outward, or L is
  // flat to rounding there: the grid value is then the answer.
  if (!(at_lo.g < 0.0 && at_hi.g > 0.0))
    return finish(s, grid_u(best), best_f, convex, evaluations);
  double u = grid_u(best);
  double du_old = hi - lo, du = du_old;
  Slope at = slope(u);
  for (int it = 0; it < o.max_iterations; ++it) {
    const bool newton_outside = ((u - hi) * at.dg - at.g) * ((u - lo) * at.dg - at.g) > 0.0;
    const bool newton_slow = std::abs(2.0 * at.g) > std::abs(du_old * at.dg);
    du_old = du;
    if (newton_outside || newton_slow || !(at.dg > 0.0)) {
      du = 0.5 * (hi - lo);
      u = lo + du;
    } else {
      du = at.g / at.dg;
      u -= du;
    }
    at = slope(u);
    if (at.g < 0.0) {
      lo = u;
    } else {
      hi = u;
    }
    if (std::abs(du) < o.tolerance_u || hi - lo < o.tolerance_u) break;
  }
  // Never worse than the grid point (guards against a flat, noisy g).
  if (sense * at.f > sense * best_f) return finish(s, grid_u(best), best_f, convex, evaluations);
  return finish(s, u, at.f, convex, evaluations);
}

StepError iterative_step_error(const StepErrorSegment& s, const IterativeStepErrorOptions& o) {
  o.validate();
  const Line line = cl_line(s);
  const bool convex = convex_against(s, line);
  const double sense = convex ? 1.0 : -1.0;
  const int n = o.points_per_pass - 1;
  double lo = s.u0, hi = s.u1, best_u = s.u0, best_f = 0.0;
  int evaluations = 3;
  const double stop = o.relative_tolerance * (s.u1 - s.u0);
  for (int pass = 0; pass < o.max_passes && hi - lo > stop; ++pass) {
    const double h = (hi - lo) / n;
    int best = -1;
    for (int k = 0; k <= n; ++k) {
      const double u = k == n ? hi : lo + h * k;
      const double f = squared_distance(line, curve_point(*s.curve, u));
      ++evaluations;
      if (best < 0 || sense * f < sense * best_f) {
        best = k;
        best_f = f;
        best_u = u;
      }
    }
    const double new_lo = std::max(lo, best_u - h), new_hi = std::min(hi, best_u + h);
    lo = new_lo;
    hi = new_hi;
  }
  return finish(s, best_u, best_f, convex, evaluations);
}

}  // namespace cnclab
