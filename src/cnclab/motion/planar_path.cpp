#include "cnclab/motion/planar_path.hpp"

#include <array>
#include <cmath>
#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

// 5-point Gauss-Legendre nodes and weights on [-1, 1].
constexpr std::array<double, 5> kGaussNodes = {-0.9061798459386640, -0.5384693101056831, 0.0,
                                               0.5384693101056831, 0.9061798459386640};
constexpr std::array<double, 5> kGaussWeights = {0.2369268850561891, 0.4786286704993665,
                                                 0.5688888888888889, 0.4786286704993665,
                                                 0.2369268850561891};

}  // namespace

double arc_length(const PlanarPath& path, double u0, double u1, int intervals) {
  const double h = (u1 - u0) / intervals;
  double total = 0.0;
  for (int k = 0; k < intervals; ++k) {
    const double mid = u0 + (k + 0.5) * h;
    for (std::size_t g = 0; g < kGaussNodes.size(); ++g) {
      total += kGaussWeights[g] * 0.5 * h * path.evaluate(mid + 0.5 * h * kGaussNodes[g]).d1.norm();
    }
  }
  return total;
}

double arc_length(const PlanarPath& path, int intervals) {
  return arc_length(path, path.u_begin(), path.u_end(), intervals);
}

double parameter_at_arc_length(const PlanarPath& path, double s) {
  double lo = path.u_begin(), hi = path.u_end();
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    (arc_length(path, path.u_begin(), mid, 256) < s ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

void RegularityOptions::validate() const {
  if (samples < 2) throw OptionError("samples", std::to_string(samples), "must be >= 2");
  if (!(min_speed_ratio > 0.0 && min_speed_ratio < 1.0)) {
    throw OptionError("min_speed_ratio", std::to_string(min_speed_ratio), "must be in (0, 1)");
  }
}

void check_regular_path(const PlanarPath& path, const RegularityOptions& options) {
  options.validate();
  const double u0 = path.u_begin();
  const double u1 = path.u_end();
  if (!(std::isfinite(u0) && std::isfinite(u1) && u1 > u0)) {
    std::ostringstream m;
    m << "path parameter range [" << u0 << ", " << u1 << "] is empty or not finite";
    throw Error(m.str());
  }
  const double mean_speed = arc_length(path) / (u1 - u0);
  const double min_speed = options.min_speed_ratio * mean_speed;
  for (int k = 0; k < options.samples; ++k) {
    const double u = u0 + (u1 - u0) * k / (options.samples - 1);
    const PathPoint p = path.evaluate(u);
    const double speed = p.d1.norm();
    if (!(speed >= min_speed) || !p.position.allFinite()) {
      std::ostringstream m;
      m << "path has a cusp or stationary point at u = " << u << ": |C'(u)| = " << speed
        << " mm per unit u, must be >= " << min_speed << " (" << options.min_speed_ratio
        << " x mean parametric speed " << mean_speed << ")";
      throw Error(m.str());
    }
  }
}

}  // namespace cnclab
