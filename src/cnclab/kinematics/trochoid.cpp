#include "cnclab/kinematics/trochoid.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr std::size_t kMaxPoints = 10'000'000;
}  // namespace

void TrochoidGrooveOptions::validate() const {
  const auto positive = [](double v, const char* field, const char* what) {
    if (!(v > 0) || !std::isfinite(v)) {
      throw OptionError(field, shortest_double(v),
                        std::string("must be a finite ") + what + " > 0");
    }
  };
  positive(cutter_diameter, "cutter_diameter", "diameter in mm");
  positive(groove_width, "groove_width", "width in mm");
  positive(groove_length, "groove_length", "length in mm");
  if (!(cutter_diameter < groove_width)) {
    throw OptionError("cutter_diameter", shortest_double(cutter_diameter),
                      "must be smaller than groove_width " + shortest_double(groove_width) +
                          " (the trochoid radius (W - D)/2 must be > 0; a cutter as wide as "
                          "the groove is plain slotting)");
  }
  if (!(groove_length >= groove_width)) {
    throw OptionError("groove_length", shortest_double(groove_length),
                      "must be at least groove_width " + shortest_double(groove_width));
  }
  const double radius = (groove_width - cutter_diameter) / 2;
  if (!(step > 0) || !std::isfinite(step)) {
    throw OptionError("step", shortest_double(step), "must be a finite advance per loop > 0 mm");
  }
  if (step > 2 * radius) {
    throw OptionError("step", shortest_double(step),
                      "must be at most 2R = W - D = " + shortest_double(2 * radius) +
                          " mm (wider steps leave material between loops)");
  }
  if (!(chord_tolerance > 0 && chord_tolerance < radius)) {
    throw OptionError("chord_tolerance", shortest_double(chord_tolerance),
                      "must be in (0, R) with R = " + shortest_double(radius) + " mm");
  }
}

Eigen::Vector2d trochoid_point(double radius, double speed, double t) {
  return {speed * t + radius * std::cos(t), radius * std::sin(t)};
}

TrochoidGroove make_trochoid_groove(const TrochoidGrooveOptions& options) {
  options.validate();
  TrochoidGroove g;
  g.options = options;
  g.radius = (options.groove_width - options.cutter_diameter) / 2;
  g.centre_start = options.groove_width / 2;
  g.centre_travel = options.groove_length - options.groove_width;
  g.loops = g.centre_travel > 0
                ? static_cast<std::size_t>(std::ceil(g.centre_travel / options.step - 1e-12))
                : 0;
  g.advance = g.loops ? g.centre_travel / static_cast<double>(g.loops) : 0.0;
  g.speed = g.advance / kTwoPi;
  const double dt_max = 2.0 * std::acos(1.0 - options.chord_tolerance / (g.radius + g.speed));
  g.samples_per_loop = static_cast<std::size_t>(std::ceil(kTwoPi / dt_max));
  g.dt = kTwoPi / static_cast<double>(g.samples_per_loop);
  const std::size_t total = (g.loops + 2) * g.samples_per_loop + 1;
  if (total > kMaxPoints) {
    throw OptionError("chord_tolerance", shortest_double(options.chord_tolerance),
                      "gives " + std::to_string(total) + " points (more than 10000000)");
  }
  const double t_loops = kTwoPi * static_cast<double>(g.loops);
  for (std::size_t k = 0; k < total; ++k) {
    const double t = g.dt * static_cast<double>(k);
    const double centre = g.centre_start + g.speed * std::clamp(t - kTwoPi, 0.0, t_loops);
    g.t.push_back(t);
    g.points.emplace_back(centre + g.radius * std::cos(t), g.radius * std::sin(t));
  }
  return g;
}

}  // namespace cnclab
