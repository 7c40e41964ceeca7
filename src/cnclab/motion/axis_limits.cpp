#include "cnclab/motion/axis_limits.hpp"

#include <cmath>
#include <sstream>
#include <string>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

void require_positive(const std::string& field, double value) {
  if (!(value > 0.0 && std::isfinite(value))) {
    std::ostringstream v;
    v << value;
    throw OptionError(field, v.str(), "must be > 0 and finite");
  }
}

}  // namespace

void AxisLimits::validate() const {
  require_positive("velocity", velocity);
  require_positive("acceleration", acceleration);
  require_positive("jerk", jerk);
}

void PlanarLimits::validate() const {
  for (std::size_t i = 0; i < axes.size(); ++i) {
    try {
      axes[i].validate();
    } catch (const OptionError& e) {
      throw OptionError("axes[" + std::to_string(i) + "]." + e.field(), e.value(), e.rule());
    }
  }
}

}  // namespace cnclab
