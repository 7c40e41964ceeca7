#include "cnclab/motion/path_speed_cap.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

double PathSpeedCap::at(double parameter) const {
  if (u.empty()) return std::numeric_limits<double>::infinity();
  if (parameter <= u.front()) return speed.front();
  if (parameter >= u.back()) return speed.back();
  const auto it = std::upper_bound(u.begin(), u.end(), parameter);
  const auto k = static_cast<std::size_t>(it - u.begin());  // u[k-1] <= parameter < u[k]
  const double w = (parameter - u[k - 1]) / (u[k] - u[k - 1]);
  return speed[k - 1] + w * (speed[k] - speed[k - 1]);
}

PathSpeedCap PathSpeedCap::uniform(std::vector<double> knots, double value) {
  PathSpeedCap cap;
  cap.speed.assign(knots.size(), value);
  cap.u = std::move(knots);
  return cap;
}

void PathSpeedCap::validate() const {
  if (u.size() != speed.size()) {
    throw OptionError("speed", std::to_string(speed.size()) + " values",
                      "must have one value per knot (" + std::to_string(u.size()) + ")");
  }
  for (std::size_t k = 0; k < u.size(); ++k) {
    if (!std::isfinite(u[k]) || (k > 0 && !(u[k] > u[k - 1]))) {
      throw OptionError("u[" + std::to_string(k) + "]", shortest_double(u[k]),
                        "must be finite and greater than the knot before");
    }
    if (!(speed[k] > 0.0 && std::isfinite(speed[k]))) {
      throw OptionError("speed[" + std::to_string(k) + "]", shortest_double(speed[k]),
                        "must be > 0 and finite [mm/s]");
    }
  }
}

}  // namespace cnclab
