#include "cnclab/data/nurbs_path.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

NurbsPlanarPath::NurbsPlanarPath(NurbsCurve curve) : curve_(std::move(curve)) {
  curve_.validate();
  for (std::size_t i = 0; i < curve_.points.size(); ++i) {
    if (curve_.points[i].z() != 0.0) {
      throw OptionError("curve control point",
                        "[" + std::to_string(i) + "].z = " + shortest_double(curve_.points[i].z()),
                        "a planar path needs z = 0");
    }
  }
}

PathPoint NurbsPlanarPath::evaluate(double u) const {
  const CurveDerivatives d = curve_derivatives(curve_, u);
  PathPoint p;
  p.position = d.point.head<2>();
  p.d1 = d.d1.head<2>();
  p.d2 = d.d2.head<2>();
  p.d3 = d.d3.head<2>();
  return p;
}

namespace {

void require_range(const char* lo_name, double lo, const char* hi_name, double hi,
                   const char* unit_rule) {
  if (!std::isfinite(lo) || !std::isfinite(hi) || !(lo < hi)) {
    throw OptionError(std::string(lo_name) + ", " + hi_name,
                      shortest_double(lo) + ", " + shortest_double(hi), unit_rule);
  }
}

}  // namespace

void RandomNurbsPathOptions::validate() const {
  if (degree < 1 || degree > 15) {
    throw OptionError("degree", std::to_string(degree), "must be in [1, 15]");
  }
  if (control_points < static_cast<std::size_t>(degree) + 1) {
    throw OptionError("control_points", std::to_string(control_points),
                      "must be >= degree + 1 = " + std::to_string(degree + 1));
  }
  require_range("x_min", x_min, "x_max", x_max, "must be finite with x_min < x_max [mm]");
  require_range("y_min", y_min, "y_max", y_max, "must be finite with y_min < y_max [mm]");
  if (!(weight_min > 0.0) || !std::isfinite(weight_max) || weight_max < weight_min) {
    throw OptionError("weight_min, weight_max",
                      shortest_double(weight_min) + ", " + shortest_double(weight_max),
                      "must be finite with 0 < weight_min <= weight_max");
  }
  if (!std::isfinite(step_min) || !std::isfinite(step_max) || !(step_min > 0.0) ||
      step_max < step_min) {
    throw OptionError("step_min, step_max",
                      shortest_double(step_min) + ", " + shortest_double(step_max),
                      "must be finite with 0 < step_min <= step_max [mm]");
  }
  const double half_side = 0.5 * std::min(x_max - x_min, y_max - y_min);
  if (step_max > half_side) {
    throw OptionError("step_max", shortest_double(step_max),
                      "must be <= half the smaller side of the work area (" +
                          shortest_double(half_side) + " mm)");
  }
  if (!(max_turn >= 0.0 && max_turn <= 180.0)) {
    throw OptionError("max_turn", shortest_double(max_turn), "must be in [0, 180] degrees");
  }
  if (!(min_curvature_radius >= 0.0) || !std::isfinite(min_curvature_radius)) {
    throw OptionError("min_curvature_radius", shortest_double(min_curvature_radius),
                      "must be finite and >= 0 [mm]");
  }
  if (max_attempts < 1) {
    throw OptionError("max_attempts", std::to_string(max_attempts), "must be >= 1");
  }
  try {
    regularity.validate();
  } catch (const OptionError& e) {
    throw OptionError("regularity." + e.field(), e.value(), e.rule());
  }
}

namespace {

NurbsCurve draw_curve(const RandomNurbsPathOptions& options, Rng& rng) {
  NurbsCurve c;
  c.degree = options.degree;
  const std::size_t n = options.control_points;
  const auto p = static_cast<std::size_t>(options.degree);
  const auto inside = [&](const Eigen::Vector2d& q) {
    return q.x() >= options.x_min && q.x() <= options.x_max && q.y() >= options.y_min &&
           q.y() <= options.y_max;
  };
  const Eigen::Vector2d centre(0.5 * (options.x_min + options.x_max),
                               0.5 * (options.y_min + options.y_max));
  const double max_turn = options.max_turn * std::numbers::pi / 180.0;
  Eigen::Vector2d q(rng.uniform(options.x_min, options.x_max),
                    rng.uniform(options.y_min, options.y_max));
  double heading = rng.uniform(-std::numbers::pi, std::numbers::pi);
  c.points.emplace_back(q.x(), q.y(), 0.0);
  // Look-ahead: about the diameter of the walk's tightest turning circle
  // (radius step_max / (2 sin(max_turn / 2))) plus one step. While the point
  // that far ahead lies outside the area, the walk turns by max_turn towards
  // the centre, so it bends away from a wall before reaching it.
  const double lookahead =
      options.step_max * (1.0 + 1.0 / std::max(std::sin(0.5 * max_turn), 1e-3));
  const auto direction = [](double angle) {
    return Eigen::Vector2d(std::cos(angle), std::sin(angle));
  };
  for (std::size_t i = 1; i < n; ++i) {
    const Eigen::Vector2d to_centre = centre - q;
    const Eigen::Vector2d ahead = direction(heading);
    const bool steer = !inside(q + lookahead * ahead);
    const double towards_centre =
        (ahead.x() * to_centre.y() - ahead.y() * to_centre.x()) >= 0.0 ? 1.0 : -1.0;
    // Up to kStepDraws (turn, length) draws for a step that stays inside.
    constexpr int kStepDraws = 32;
    bool placed = false;
    for (int draw = 0; draw < kStepDraws && !placed; ++draw) {
      const double turned =
          heading + (steer ? towards_centre * max_turn : rng.uniform(-max_turn, max_turn));
      const double step = rng.uniform(options.step_min, options.step_max);
      const Eigen::Vector2d next = q + step * direction(turned);
      if (inside(next)) {
        q = next;
        heading = turned;
        placed = true;
      }
    }
    if (!placed) {
      // Cornered: head for the centre, at most up to it (q != centre:
      // validate() keeps step_max within half the smaller side, so a step
      // from the centre never leaves). The sharp turn is left to the
      // curvature check.
      heading = std::atan2(to_centre.y(), to_centre.x());
      q += std::min(options.step_min, to_centre.norm()) * to_centre.normalized();
    }
    c.points.emplace_back(q.x(), q.y(), 0.0);
  }
  c.weights.assign(n, options.weight_min);
  if (options.weight_min < options.weight_max) {
    for (double& w : c.weights) w = rng.uniform(options.weight_min, options.weight_max);
  }
  // Clamped: p + 1 zeros, n - p - 1 uniform interior knots, p + 1 ones.
  c.knots.assign(p + 1, 0.0);
  const std::size_t spans = n - p;
  for (std::size_t i = 1; i < spans; ++i) {
    c.knots.push_back(static_cast<double>(i) / static_cast<double>(spans));
  }
  c.knots.insert(c.knots.end(), p + 1, 1.0);
  return c;
}

// Throws cnclab::Error naming u where the radius of curvature is below the
// minimum (run after the cusp check, so |C'| > 0).
void check_curvature(const PlanarPath& path, const RandomNurbsPathOptions& options) {
  if (options.min_curvature_radius == 0.0) return;
  const int samples = options.regularity.samples;
  for (int k = 0; k < samples; ++k) {
    const double u = path.u_begin() + (path.u_end() - path.u_begin()) * k / (samples - 1);
    const PathPoint p = path.evaluate(u);
    const double cross = std::abs(p.d1.x() * p.d2.y() - p.d1.y() * p.d2.x());
    const double speed = p.d1.norm();
    // radius = |C'|^3 / cross < min  <=>  |C'|^3 < min * cross (no division).
    if (speed * speed * speed < options.min_curvature_radius * cross) {
      throw Error("radius of curvature " + shortest_double(speed * speed * speed / cross) +
                  " mm at u = " + shortest_double(u) + " is below min_curvature_radius = " +
                  shortest_double(options.min_curvature_radius) + " mm");
    }
  }
}

}  // namespace

NurbsCurve random_planar_nurbs(const RandomNurbsPathOptions& options, Rng& rng) {
  options.validate();
  std::string last;
  for (int attempt = 0; attempt < options.max_attempts; ++attempt) {
    NurbsCurve c = draw_curve(options, rng);
    const NurbsPlanarPath path(c);
    try {
      check_regular_path(path, options.regularity);
      check_curvature(path, options);
      return c;
    } catch (const Error& e) {  // options were validated: a rejected curve
      last = e.what();
    }
  }
  throw Error("random NURBS path (degree " + std::to_string(options.degree) + ", " +
              std::to_string(options.control_points) + " control points): no curve of " +
              std::to_string(options.max_attempts) + " attempts passed; last: " + last);
}

}  // namespace cnclab
