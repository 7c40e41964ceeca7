#include "cnclab/studies/contour_error/margin_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/motion/axis_direction.hpp"

namespace cnclab {
namespace {

// The metadata row `name` of the plans; cnclab::Error when absent.
Eigen::Index calibration_row(const Dataset& d, const std::string& name) {
  const Eigen::Index row = d.metadata_row(name);
  if (row < 0) {
    throw Error("margin calibration: the plans (" + d.generator + ") have no metadata column " +
                name + " (a following_error dataset has)");
  }
  return row;
}

ResidualSummary calibration_summary(const std::vector<double>& predicted,
                                    const std::vector<double>& simulated) {
  ResidualSummary s;
  s.ticks = predicted.size();
  if (s.ticks == 0) return s;
  std::vector<double> r(s.ticks);
  double sq = 0, mp = 0, ms = 0;
  for (std::size_t i = 0; i < s.ticks; ++i) {
    r[i] = simulated[i] - predicted[i];
    sq += r[i] * r[i];
    mp += predicted[i];
    ms += simulated[i];
  }
  const auto n = static_cast<double>(s.ticks);
  mp /= n;
  ms /= n;
  double cov = 0, vp = 0, vs = 0;
  for (std::size_t i = 0; i < s.ticks; ++i) {
    cov += (predicted[i] - mp) * (simulated[i] - ms);
    vp += (predicted[i] - mp) * (predicted[i] - mp);
    vs += (simulated[i] - ms) * (simulated[i] - ms);
  }
  s.rms = std::sqrt(sq / n);
  s.correlation = vp > 0 && vs > 0 ? cov / std::sqrt(vp * vs) : NAN;
  s.underprediction_max = *std::max_element(r.begin(), r.end());
  s.underprediction_p99 = empirical_quantile(r, 0.99);
  return s;
}

}  // namespace

void MarginCalibrationOptions::validate() const {
  if (!(quantile > 0.0 && quantile < 1.0)) {
    throw OptionError("quantile", shortest_double(quantile), "must be in (0, 1)");
  }
  for (std::size_t i = 0; i < feed_bands.size(); ++i) {
    if (!(feed_bands[i] > 0.0 && std::isfinite(feed_bands[i])) ||
        (i > 0 && !(feed_bands[i] > feed_bands[i - 1]))) {
      throw OptionError("feed_bands", shortest_double(feed_bands[i]),
                        "band edges must be finite, > 0 and ascending [mm/s]");
    }
  }
  if (min_ticks < 1) throw OptionError("min_ticks", "0", "must be >= 1");
  if (!(reversal_window >= 0.0 && std::isfinite(reversal_window))) {
    throw OptionError("reversal_window", shortest_double(reversal_window),
                      "must be >= 0 and finite [s]");
  }
}

double empirical_quantile(std::vector<double>& values, double q) {
  if (values.empty()) return NAN;
  const auto n = static_cast<double>(values.size());
  const auto k = static_cast<std::size_t>(std::max(1.0, std::ceil(q * n - 1e-9))) - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

MarginCalibration calibrate_margins(ContourPredictor& predictor, const Dataset& plans,
                                    const MarginCalibrationOptions& options) {
  options.validate();
  const Dataset& d = plans;
  const Eigen::Index vx = calibration_row(d, "v_ref_x"), vy = calibration_row(d, "v_ref_y"),
                     rx = calibration_row(d, "ref_x"), ry = calibration_row(d, "ref_y"),
                     d1x = calibration_row(d, "d1_x"), d1y = calibration_row(d, "d1_y"),
                     d2x = calibration_row(d, "d2_x"), d2y = calibration_row(d, "d2_y"),
                     exact = calibration_row(d, "contour_exact"),
                     validation = calibration_row(d, "validation");
  const Eigen::Index factor_row = d.metadata_row("feed_factor");
  const Eigen::Index piece_row = d.metadata_row("piece");  // a cold start where it changes
  // The runs of the path: samples of one feed factor in dataset order (its
  // first half, then its second: generation order); one run without factors.
  std::map<double, std::vector<Eigen::Index>> runs;
  for (Eigen::Index k = 0; k < d.metadata.cols(); ++k) {
    runs[factor_row < 0 ? 1.0 : d.metadata(factor_row, k)].push_back(k);
  }
  const std::size_t bands = options.feed_bands.size() + 1;
  const bool window = options.reversal_window > 0.0;
  // [class][band]: class 1 within the reversal window.
  std::vector<std::vector<double>> by_band[2] = {std::vector<std::vector<double>>(bands),
                                                 std::vector<std::vector<double>>(bands)};
  std::vector<double> all_r, val_pred, val_sim, slow_pred, slow_sim;
  FeedBandMargins locate;  // for band() and after_reversal_at(): edges and window only
  locate.edges = options.feed_bands;
  locate.reversal_window = options.reversal_window;
  // The time since a change of direction, counted in the dataset's ticks.
  if (runs.empty()) throw Error("margin calibration: the plans have no samples");
  AxisDirectionOptions clock;
  const std::vector<Eigen::Index>& first_run = runs.begin()->second;
  if (const Eigen::Index t = d.metadata_row("time"); t >= 0 && first_run.size() > 1) {
    const double period = d.metadata(t, first_run[1]) - d.metadata(t, first_run[0]);
    if (period > 0.0 && std::isfinite(period)) clock.period = period;
  }
  AxisDirection turn_x(clock), turn_y(clock);
  for (const auto& [factor, samples] : runs) {
    double piece = NAN;
    for (const Eigen::Index k : samples) {
      const double here = piece_row < 0 ? 0.0 : d.metadata(piece_row, k);
      if (here != piece) {
        predictor.reset();
        turn_x.reset();
        turn_y.reset();
      }
      piece = here;
      turn_x.step(d.metadata(vx, k));
      turn_y.step(d.metadata(vy, k));
      PathPoint p;
      p.position = {d.metadata(rx, k), d.metadata(ry, k)};
      p.d1 = {d.metadata(d1x, k), d.metadata(d1y, k)};
      p.d2 = {d.metadata(d2x, k), d.metadata(d2y, k)};
      const Vec2 v(d.metadata(vx, k), d.metadata(vy, k));
      ContourPrediction out;
      const PredictorStatus status = predictor.step(v, p, out);
      if (status != PredictorStatus::ok) {
        throw Error("margin calibration: the predictor rejected sample " + std::to_string(k) +
                    " of the plans: " + to_string(status));
      }
      if (d.metadata(validation, k) != 1.0) continue;
      const double predicted = std::abs(out.contour_error), simulated = d.metadata(exact, k) * 1e-3;
      const double r = simulated - predicted;
      const bool after_reversal =
          locate.after_reversal_at(std::min(turn_x.since_change(), turn_y.since_change()));
      by_band[after_reversal ? 1 : 0][locate.band(v.norm())].push_back(r);
      all_r.push_back(r);
      val_pred.push_back(predicted);
      val_sim.push_back(simulated);
      if (factor < 1.0) {
        slow_pred.push_back(predicted);
        slow_sim.push_back(simulated);
      }
    }
  }
  if (all_r.empty()) throw Error("margin calibration: the plans have no validation tick");
  MarginCalibration c;
  c.margins.edges = options.feed_bands;
  const double overall = std::max(0.0, empirical_quantile(all_r, options.quantile));
  // The margins of one class per band; a band with fewer than min_ticks
  // takes the quantile of its class, or of all ticks.
  const auto class_margins = [&](std::vector<std::vector<double>>& classes,
                                 std::vector<double>& margins, std::vector<std::size_t>& ticks) {
    std::vector<double> pooled;
    for (const auto& r : classes) pooled.insert(pooled.end(), r.begin(), r.end());
    const double fallback = pooled.size() < options.min_ticks
                                ? overall
                                : std::max(0.0, empirical_quantile(pooled, options.quantile));
    for (auto& r : classes) {
      ticks.push_back(r.size());
      margins.push_back(r.size() < options.min_ticks
                            ? fallback
                            : std::max(0.0, empirical_quantile(r, options.quantile)));
    }
  };
  class_margins(by_band[0], c.margins.margin, c.band_ticks);
  if (window) {
    c.margins.reversal_window = options.reversal_window;
    class_margins(by_band[1], c.margins.after_reversal, c.after_reversal_band_ticks);
  }
  c.validation = calibration_summary(val_pred, val_sim);
  c.slowed = calibration_summary(slow_pred, slow_sim);
  return c;
}

}  // namespace cnclab
