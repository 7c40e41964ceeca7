#pragma once
// Least-squares fit of a trochoid to sampled points (t_i, x_i, y_i): how
// seed 004's Table 3 relates to its Eq. 6. Model: Eq. 6 with an offset, a
// phase and the advance in any direction of the plane,
//   x = x0 + Vx t + R cos(w t + phi),   y = y0 + Vy t + R sin(w t + phi),
// fitted by Levenberg-Marquardt (analytic Jacobian, Marquardt's diagonal
// scaling) from a grid of starting (w, phi); optionally with R fixed.
#include <Eigen/Core>
#include <optional>
#include <span>

namespace cnclab {

struct TrochoidParameters {
  double x0 = 0, y0 = 0;  // offset [mm]
  double vx = 0, vy = 0;  // advance velocity (Eq. 6's V along x: vx = V, vy = 0) [mm per unit t]
  double radius = 0;      // R [mm] (> 0 in a fit's result)
  double omega = 0;       // w [rad per unit t]
  double phase = 0;       // phi [rad] (in [-pi, pi] in a fit's result)
};

Eigen::Vector2d trochoid_model(const TrochoidParameters& p, double t);

struct TrochoidFit {
  TrochoidParameters parameters;
  double rms = 0;           // sqrt(mean over points of |model - point|^2) [mm]
  double max_residual = 0;  // largest |model - point| [mm]
};

// Advance per revolution of the circling point: 2 pi |V| / |w| [mm].
double advance_per_turn(const TrochoidParameters& p);

// t and points of equal size >= 8 (7 parameters); throws cnclab::Error
// otherwise. fixed_radius: fit with R held at this value.
TrochoidFit fit_trochoid(std::span<const double> t, std::span<const Eigen::Vector2d> points,
                         std::optional<double> fixed_radius = std::nullopt);

}  // namespace cnclab
