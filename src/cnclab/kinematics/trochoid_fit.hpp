#pragma once
// Least-squares fit of a trochoid to sampled points (t_i, x_i, y_i): how
// seed 004's Table 3 relates to its Eq. 6. Model: Eq. 6 with an offset and
// a phase,
//   x = x0 + V t + R cos(w t + phi),   y = y0 + R sin(w t + phi),
// fitted by Levenberg-Marquardt (analytic Jacobian, Marquardt's diagonal
// scaling) from a grid of starting (w, phi); optionally with R fixed.
#include <Eigen/Core>
#include <optional>
#include <span>

namespace cnclab {

struct TrochoidParameters {
  double x0 = 0, y0 = 0;  // offset [mm]
  double speed = 0;       // V [mm per unit t]
  double radius = 0;      // R [mm]
  double omega = 0;       // w [rad per unit t]
  double phase = 0;       // phi [rad]
};

Eigen::Vector2d trochoid_model(const TrochoidParameters& p, double t);

struct TrochoidFit {
  TrochoidParameters parameters;
  double rms = 0;           // sqrt(mean over points of |model - point|^2) [mm]
  double max_residual = 0;  // largest |model - point| [mm]
};

// t and points of equal size >= 7 (6 parameters); throws cnclab::Error
// otherwise. fixed_radius: fit with R held at this value.
TrochoidFit fit_trochoid(std::span<const double> t, std::span<const Eigen::Vector2d> points,
                         std::optional<double> fixed_radius = std::nullopt);

}  // namespace cnclab
