#include "cnclab/motion/feedrate_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "cnclab/motion/path_grid.hpp"
#include "cnclab/motion/scurve.hpp"

namespace cnclab {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// Feasible range [lo, hi] of a = d2u/dt2 at a point with b = (du/dt)^2 under
// the acceleration limits; lo > hi when there is none.
struct Range {
  double lo = -kInf, hi = kInf;
};

Range acceleration_range(const PathPoint& p, double b, const PlanarLimits& limits) {
  Range r;
  for (int i = 0; i < 2; ++i) {
    const double A = limits.axes[i].acceleration;
    const double c1 = p.d1[i], c2 = p.d2[i];
    if (c1 == 0.0) {
      if (std::abs(c2) * b > A) return {1.0, -1.0};
      continue;
    }
    double lo = (-A - c2 * b) / c1, hi = (A - c2 * b) / c1;
    if (c1 < 0.0) std::swap(lo, hi);
    r.lo = std::max(r.lo, lo);
    r.hi = std::min(r.hi, hi);
  }
  return r;
}

// Largest b on the maximum-velocity curve (the feasible b form an interval
// [0, b_max] because the feasible (a, b) set is a convex polygon containing
// (0, 0)).
double max_b(const PathPoint& p, const PlanarLimits& limits) {
  double b_vel = kInf;
  for (int i = 0; i < 2; ++i) {
    const double c1 = std::abs(p.d1[i]);
    if (c1 > 0.0) b_vel = std::min(b_vel, std::pow(limits.axes[i].velocity / c1, 2));
  }
  auto feasible = [&](double b) {
    const Range r = acceleration_range(p, b, limits);
    return r.lo <= r.hi;
  };
  if (feasible(b_vel)) return b_vel;
  double lo = 0.0, hi = b_vel;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (feasible(mid) ? lo : hi) = mid;
  }
  return lo;
}

}  // namespace

double velocity_acceleration_time(const PlanarPath& path, const PlanarLimits& limits,
                                  double spacing) {
  limits.validate();
  const std::vector<double> u = arc_length_grid(path, spacing, 2);
  const std::size_t n = u.size();
  std::vector<PathPoint> points(n);
  std::vector<double> b(n);
  for (std::size_t k = 0; k < n; ++k) {
    points[k] = path.evaluate(u[k]);
    b[k] = max_b(points[k], limits);
  }
  b.front() = 0.0;
  b.back() = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Range r = acceleration_range(points[k], b[k], limits);
    const double a = r.lo <= r.hi ? std::max(r.hi, 0.0) : 0.0;
    b[k + 1] = std::min(b[k + 1], b[k] + 2.0 * (u[k + 1] - u[k]) * a);
  }
  for (std::size_t k = n - 1; k > 0; --k) {
    const Range r = acceleration_range(points[k], b[k], limits);
    const double a = r.lo <= r.hi ? std::min(r.lo, 0.0) : 0.0;
    b[k - 1] = std::min(b[k - 1], b[k] - 2.0 * (u[k] - u[k - 1]) * a);
  }
  double time = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    time += 2.0 * (u[k + 1] - u[k]) / (std::sqrt(b[k]) + std::sqrt(b[k + 1]));
  }
  return time;
}

ConstantFeedrateProfile constant_feedrate_time(const PlanarPath& path, const PlanarLimits& limits,
                                               int samples, double max_feed) {
  limits.validate();
  Vec2 m0 = Vec2::Zero(), m1 = Vec2::Zero(), m2 = Vec2::Zero();
  for (int k = 0; k < samples; ++k) {
    const double u = path.u_begin() + (path.u_end() - path.u_begin()) * k / (samples - 1);
    const PathPoint p = path.evaluate(u);
    // Arc-length derivatives of T = C'/sigma, sigma = |C'|:
    //   dT/ds = P / sigma^2,  P = C'' - T (T.C'');
    //   d2T/ds2 = (P' / sigma^2 - 2 P (T.C'') / sigma^3) / sigma,
    //   P' = C''' - T' (T.C'') - T (T'.C'' + T.C'''),  T' = dT/du = P / sigma.
    const double sigma = p.d1.norm();
    const Vec2 T = p.d1 / sigma;
    const double tc2 = T.dot(p.d2);
    const Vec2 P = p.d2 - T * tc2;
    const Vec2 Tu = P / sigma;
    const Vec2 dP = p.d3 - Tu * tc2 - T * (Tu.dot(p.d2) + T.dot(p.d3));
    const Vec2 Ts = P / (sigma * sigma);
    const Vec2 Tss = (dP / (sigma * sigma) - 2.0 * P * tc2 / (sigma * sigma * sigma)) / sigma;
    m0 = m0.cwiseMax(T.cwiseAbs());
    m1 = m1.cwiseMax(Ts.cwiseAbs());
    m2 = m2.cwiseMax(Tss.cwiseAbs());
  }
  const double length = arc_length(path);
  // Largest cruise feedrate: every limit with a_t = j_t = 0.
  double f_max = kInf;
  for (int i = 0; i < 2; ++i) {
    const AxisLimits& L = limits.axes[i];
    if (m0[i] > 0) f_max = std::min(f_max, L.velocity / m0[i]);
    if (m1[i] > 0) f_max = std::min(f_max, std::sqrt(L.acceleration / m1[i]));
    if (m2[i] > 0) f_max = std::min(f_max, std::cbrt(L.jerk / m2[i]));
  }
  f_max = std::min(f_max, max_feed);
  ConstantFeedrateProfile best;
  best.time = kInf;
  constexpr int kFeedSteps = 400, kAccelSteps = 100;
  for (int f = 1; f <= kFeedSteps; ++f) {
    const double F = f_max * f / kFeedSteps;
    double a_cap = kInf;
    for (int i = 0; i < 2; ++i) {
      if (m0[i] > 0) a_cap = std::min(a_cap, (limits.axes[i].acceleration - F * F * m1[i]) / m0[i]);
    }
    for (int s = 1; s <= kAccelSteps && a_cap > 0; ++s) {
      const double a_t = a_cap * s / kAccelSteps;
      double j_t = kInf;
      for (int i = 0; i < 2; ++i) {
        if (m0[i] > 0) {
          j_t = std::min(j_t,
                         (limits.axes[i].jerk - 3 * F * a_t * m1[i] - F * F * F * m2[i]) / m0[i]);
        }
      }
      if (!(j_t > 0)) continue;
      const double t = scurve_time(length, F, a_t, j_t);
      if (t < best.time) best = {t, F, a_t, j_t};
    }
  }
  return best;
}

}  // namespace cnclab
