#include "cnclab/kinematics/trochoid_fit.hpp"

#include <Eigen/Cholesky>
#include <cmath>
#include <numbers>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

constexpr int kMaxIterations = 500;

// Parameter vector order: x0, y0, Vx, Vy, R, w, phi (R dropped when fixed).
TrochoidParameters unpack(const Eigen::VectorXd& v, std::optional<double> fixed_radius) {
  TrochoidParameters p;
  int i = 0;
  p.x0 = v[i++];
  p.y0 = v[i++];
  p.vx = v[i++];
  p.vy = v[i++];
  p.radius = fixed_radius ? *fixed_radius : v[i++];
  p.omega = v[i++];
  p.phase = v[i++];
  return p;
}

double cost(const TrochoidParameters& p, std::span<const double> t,
            std::span<const Eigen::Vector2d> pts) {
  double s = 0;
  for (std::size_t i = 0; i < t.size(); ++i) s += (trochoid_model(p, t[i]) - pts[i]).squaredNorm();
  return s;
}

Eigen::VectorXd levenberg_marquardt(Eigen::VectorXd v, std::span<const double> t,
                                    std::span<const Eigen::Vector2d> pts,
                                    std::optional<double> fixed_radius) {
  const auto m = static_cast<Eigen::Index>(2 * t.size());
  const auto n = v.size();
  double lambda = 1e-3;
  double f = cost(unpack(v, fixed_radius), t, pts);
  for (int it = 0; it < kMaxIterations; ++it) {
    const TrochoidParameters p = unpack(v, fixed_radius);
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(m, n);
    Eigen::VectorXd r(m);
    for (std::size_t i = 0; i < t.size(); ++i) {
      const double a = p.omega * t[i] + p.phase, ca = std::cos(a), sa = std::sin(a);
      const auto rx = static_cast<Eigen::Index>(2 * i), ry = rx + 1;
      const Eigen::Vector2d model = trochoid_model(p, t[i]);
      r[rx] = model.x() - pts[i].x();
      r[ry] = model.y() - pts[i].y();
      Eigen::Index c = 0;
      j(rx, c++) = 1;     // x0
      j(ry, c++) = 1;     // y0
      j(rx, c++) = t[i];  // Vx
      j(ry, c++) = t[i];  // Vy
      if (!fixed_radius) {
        j(rx, c) = ca;  // R
        j(ry, c++) = sa;
      }
      j(rx, c) = -p.radius * sa * t[i];  // w
      j(ry, c++) = p.radius * ca * t[i];
      j(rx, c) = -p.radius * sa;  // phi
      j(ry, c) = p.radius * ca;
    }
    const Eigen::MatrixXd jtj = j.transpose() * j;
    const Eigen::VectorXd g = j.transpose() * r;
    bool improved = false;
    while (lambda < 1e12) {
      Eigen::MatrixXd a = jtj;
      a.diagonal() += lambda * jtj.diagonal().cwiseMax(1e-12);
      const Eigen::VectorXd step = a.ldlt().solve(-g);
      const Eigen::VectorXd trial = v + step;
      const double f_trial = cost(unpack(trial, fixed_radius), t, pts);
      if (std::isfinite(f_trial) && f_trial < f) {
        const double decrease = f - f_trial;
        v = trial;
        f = f_trial;
        lambda = std::max(lambda / 10, 1e-15);
        improved = decrease > 1e-15 * (1 + f);
        break;
      }
      lambda *= 10;
    }
    if (!improved) break;
  }
  return v;
}

}  // namespace

Eigen::Vector2d trochoid_model(const TrochoidParameters& p, double t) {
  const double a = p.omega * t + p.phase;
  return {p.x0 + p.vx * t + p.radius * std::cos(a), p.y0 + p.vy * t + p.radius * std::sin(a)};
}

double advance_per_turn(const TrochoidParameters& p) {
  return 2 * std::numbers::pi * std::hypot(p.vx, p.vy) / std::abs(p.omega);
}

TrochoidFit fit_trochoid(std::span<const double> t, std::span<const Eigen::Vector2d> points,
                         std::optional<double> fixed_radius) {
  if (t.size() != points.size() || t.size() < 8) {
    throw Error("trochoid fit: need equal numbers (>= 8) of parameters and points, got " +
                std::to_string(t.size()) + " and " + std::to_string(points.size()));
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  double spread = 0;
  for (const auto& p : points) spread = std::max(spread, (p - mean).norm());
  const double t_span = t.back() - t.front();
  TrochoidFit best;
  double best_cost = INFINITY;
  // Starting angular rates: from a twentieth of a turn to four turns over
  // the sampled span; phases every quarter turn.
  for (double turns : {0.05, 0.1, 0.2, 0.35, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0}) {
    for (int q = 0; q < 4; ++q) {
      const double omega = 2 * std::numbers::pi * turns / (t_span > 0 ? t_span : 1.0);
      const double phase = q * std::numbers::pi / 2;
      const double radius = fixed_radius.value_or(spread > 0 ? spread : 1.0);
      Eigen::VectorXd v(fixed_radius ? 6 : 7);
      if (fixed_radius) {
        v << mean.x() - radius * std::cos(phase), mean.y() - radius * std::sin(phase), 0.0, 0.0,
            omega, phase;
      } else {
        v << mean.x() - radius * std::cos(phase), mean.y() - radius * std::sin(phase), 0.0, 0.0,
            radius, omega, phase;
      }
      v = levenberg_marquardt(v, t, points, fixed_radius);
      const TrochoidParameters p = unpack(v, fixed_radius);
      const double c = cost(p, t, points);
      if (c < best_cost) {
        best_cost = c;
        best.parameters = p;
      }
    }
  }
  // (R, phi) and (-R, phi + pi) describe the same curve: report R > 0 and
  // phi in [-pi, pi].
  if (best.parameters.radius < 0) {
    best.parameters.radius = -best.parameters.radius;
    best.parameters.phase += std::numbers::pi;
  }
  best.parameters.phase = std::remainder(best.parameters.phase, 2 * std::numbers::pi);
  best.rms = std::sqrt(best_cost / static_cast<double>(t.size()));
  for (std::size_t i = 0; i < t.size(); ++i) {
    best.max_residual =
        std::max(best.max_residual, (trochoid_model(best.parameters, t[i]) - points[i]).norm());
  }
  return best;
}

}  // namespace cnclab
