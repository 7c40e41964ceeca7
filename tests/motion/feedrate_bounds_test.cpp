// The constant-feedrate upper bound is the time of a feasible motion: run
// that S-curve along the path's arc length, sample it at 1 ms, and find every
// axis limit held by numerical differentiation of the positions.
#include "cnclab/motion/feedrate_bounds.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cnclab/motion/scurve.hpp"
#include "planned_paths.hpp"

namespace cnclab {
namespace {

constexpr double kLimitTolerance = 0.01;

// Rest-to-rest S-curve over `length` with limits (v, a, j), built from its
// phases (peak velocity by bisection on the covered distance), sampled every
// dt: the arc length s(t_k).
std::vector<double> scurve_samples(double length, double v, double a, double j, double dt) {
  auto ramp = [&](double vp, double* tj, double* ta) {
    const double ap = std::min(a, std::sqrt(vp * j));
    *tj = ap / j;
    *ta = vp / ap - *tj;
    return 0.5 * vp * (2 * *tj + *ta);  // ramp distance
  };
  double lo = 0, hi = v, tj = 0, ta = 0;
  for (int it = 0; it < 200; ++it) {
    const double mid = 0.5 * (lo + hi);
    (2 * ramp(mid, &tj, &ta) <= length ? lo : hi) = mid;
  }
  const double vp = lo;
  const double tv = (length - 2 * ramp(vp, &tj, &ta)) / vp;
  const double phases[7] = {tj, ta, tj, tv, tj, ta, tj};
  const double jerks[7] = {j, 0, -j, 0, -j, 0, j};
  std::vector<double> s;
  double x = 0, vel = 0, acc = 0, t_phase = 0, t = 0;
  for (int p = 0; p < 7; ++p) {
    for (; t < t_phase + phases[p]; t += dt) {
      const double tau = t - t_phase;
      s.push_back(x + vel * tau + acc * tau * tau / 2 + jerks[p] * tau * tau * tau / 6);
    }
    const double T = phases[p];
    x += vel * T + acc * T * T / 2 + jerks[p] * T * T * T / 6;
    vel += acc * T + jerks[p] * T * T / 2;
    acc += jerks[p] * T;
    t_phase += T;
  }
  for (int k = 0; k < 3; ++k) s.push_back(length);  // at rest
  return s;
}

// Parameter at arc length s: a fine table, then Newton on s(u) - s.
class ArcLengthInverse {
 public:
  explicit ArcLengthInverse(const PlanarPath& path) : path_(path) {
    const int n = 20000;
    for (int k = 0; k <= n; ++k) {
      u_.push_back(path.u_begin() + (path.u_end() - path.u_begin()) * k / n);
      s_.push_back(k == 0 ? 0.0 : s_.back() + arc_length(path, u_[k - 1], u_[k], 1));
    }
  }
  double operator()(double s) const {
    const auto it = std::upper_bound(s_.begin(), s_.end(), s);
    const std::size_t i = std::clamp<std::size_t>(it - s_.begin(), 1, s_.size() - 1) - 1;
    double u = u_[i] + (u_[i + 1] - u_[i]) * (s - s_[i]) / (s_[i + 1] - s_[i]);
    for (int it2 = 0; it2 < 4; ++it2) {
      u -= (s_[i] + arc_length(path_, u_[i], u, 1) - s) / path_.evaluate(u).d1.norm();
    }
    return u;
  }

 private:
  const PlanarPath& path_;
  std::vector<double> u_, s_;
};

TEST(FeedrateBounds, ConstantFeedrateProfileIsFeasible) {
  const PlanarLimits limits;
  for (const char* name : {"circle", "bezier", "epitrochoid"}) {
    const PlanarPath& path = *testing::planned_path(name).path;
    const ConstantFeedrateProfile bound = constant_feedrate_time(path, limits);
    const double h = 1e-3;
    const std::vector<double> s = scurve_samples(
        arc_length(path), bound.feedrate, bound.tangential_acceleration, bound.tangential_jerk, h);
    EXPECT_NEAR((s.size() - 3) * h, bound.time, 2 * h) << name;  // the same motion
    const ArcLengthInverse u_of_s(path);
    std::vector<Vec2> p;
    for (const double sk : s) p.push_back(path.evaluate(u_of_s(sk)).position);
    Vec2 v_max = Vec2::Zero(), a_max = Vec2::Zero(), j_max = Vec2::Zero();
    for (std::size_t k = 2; k + 2 < p.size(); ++k) {
      v_max = v_max.cwiseMax(((p[k + 1] - p[k - 1]) / (2 * h)).cwiseAbs());
      a_max = a_max.cwiseMax(((p[k + 1] - 2 * p[k] + p[k - 1]) / (h * h)).cwiseAbs());
      j_max = j_max.cwiseMax(
          ((p[k + 2] - 2 * p[k + 1] + 2 * p[k - 1] - p[k - 2]) / (2 * h * h * h)).cwiseAbs());
    }
    std::printf("%-12s F = %.1f mm/s: peak |v| %.1f %.1f  |a| %.0f %.0f  |j| %.0f %.0f\n", name,
                bound.feedrate, v_max.x(), v_max.y(), a_max.x(), a_max.y(), j_max.x(), j_max.y());
    for (int i = 0; i < 2; ++i) {
      EXPECT_LE(v_max[i], limits.axes[i].velocity * (1 + kLimitTolerance)) << name;
      EXPECT_LE(a_max[i], limits.axes[i].acceleration * (1 + kLimitTolerance)) << name;
      EXPECT_LE(j_max[i], limits.axes[i].jerk * (1 + kLimitTolerance)) << name;
    }
  }
}

}  // namespace
}  // namespace cnclab
