#pragma once
// A path-speed upper bound along a planar path, |C'(u)| du/dt <= cap(u)
// [mm/s], as a piecewise-linear function of the path parameter. The feedrate
// planner imposes it at its grid nodes beside the axis limits (a bound on
// the NLP's v_k, feedrate_nlp.hpp); the contour-error feedrate optimisation
// (studies/contour_error/feedrate_optimisation.hpp) lowers it where the
// predicted contour error is too large.
#include <vector>

namespace cnclab {

struct PathSpeedCap {
  // Knots: strictly increasing parameters and the cap there [mm/s], > 0.
  // Empty = no cap. Between knots the cap is linear in u; before the first
  // and after the last knot it is the end value.
  std::vector<double> u, speed;

  bool empty() const { return u.empty(); }
  // cap(u) as above; +infinity when empty.
  double at(double parameter) const;
  // A cap of `speed` at every knot `u`.
  static PathSpeedCap uniform(std::vector<double> u, double speed);

  // OptionError naming the field: equal sizes, u strictly increasing and
  // finite, every speed > 0 and finite.
  void validate() const;
};

}  // namespace cnclab
