#include "cnclab/motion/axis_direction.hpp"

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

const char* to_string(AxisFeature feature) noexcept {
  switch (feature) {
    case AxisFeature::sign:
      return "sign";
    case AxisFeature::direction:
      return "direction";
    case AxisFeature::reversal:
      return "reversal";
  }
  return "unknown";
}

bool parse_axis_feature(const std::string& name, AxisFeature& out) noexcept {
  for (const AxisFeature f : {AxisFeature::sign, AxisFeature::direction, AxisFeature::reversal}) {
    if (name == to_string(f)) {
      out = f;
      return true;
    }
  }
  return false;
}

void AxisDirectionOptions::validate() const {
  if (!(deadband >= 0.0 && std::isfinite(deadband))) {
    throw OptionError("deadband", shortest_double(deadband), "must be >= 0 and finite [mm/s]");
  }
  if (!(reversal_time_constant > 0.0 && std::isfinite(reversal_time_constant))) {
    throw OptionError("reversal_time_constant", shortest_double(reversal_time_constant),
                      "must be > 0 and finite [s]");
  }
  if (!(period > 0.0 && std::isfinite(period))) {
    throw OptionError("period", shortest_double(period), "must be > 0 and finite [s]");
  }
}

AxisDirection::AxisDirection(AxisDirectionOptions options)
    : options_((options.validate(), options)),
      per_tick_(std::exp(-options_.period / options_.reversal_time_constant)) {}

void AxisDirection::reset() noexcept {
  sign_ = 0.0;
  direction_ = 0.0;
  decay_ = 1.0;
  ticks_since_change_ = -1;
}

void AxisDirection::step(double velocity) noexcept {
  const bool moving = std::isfinite(velocity) && std::abs(velocity) > options_.deadband;
  sign_ = moving ? (velocity > 0.0 ? 1.0 : -1.0) : 0.0;
  if (moving && sign_ != direction_) {
    direction_ = sign_;
    decay_ = 1.0;  // t_c = this tick
    ticks_since_change_ = 0;
  } else {
    if (ticks_since_change_ >= 0) ++ticks_since_change_;
    // Flushed to 0 long after the change (no denormals on long runs).
    decay_ = decay_ < 1e-12 ? 0.0 : decay_ * per_tick_;
  }
}

double AxisDirection::reversal() const noexcept {
  return direction_ * decay_;
}

double AxisDirection::since_change() const noexcept {
  return ticks_since_change_ < 0 ? INFINITY
                                 : static_cast<double>(ticks_since_change_) * options_.period;
}

double AxisDirection::value(AxisFeature feature) const noexcept {
  switch (feature) {
    case AxisFeature::sign:
      return sign_;
    case AxisFeature::direction:
      return direction_;
    case AxisFeature::reversal:
      return reversal();
  }
  return 0.0;
}

std::vector<std::vector<double>> axis_direction_series(const std::vector<double>& velocity,
                                                       const std::vector<AxisFeature>& features,
                                                       const AxisDirectionOptions& options) {
  AxisDirection axis(options);
  std::vector<std::vector<double>> out(features.size(), std::vector<double>(velocity.size()));
  for (std::size_t t = 0; t < velocity.size(); ++t) {
    axis.step(velocity[t]);
    for (std::size_t f = 0; f < features.size(); ++f) out[f][t] = axis.value(features[f]);
  }
  return out;
}

}  // namespace cnclab
