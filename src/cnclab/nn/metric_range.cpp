#include "cnclab/nn/metric_range.hpp"

#include <cmath>

#include "cnclab/core/format.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {

bool MetricRange::bounded() const {
  return std::isfinite(low) || std::isfinite(high);
}

std::string MetricRange::text() const {
  if (std::isfinite(low) && std::isfinite(high)) {
    return "in [" + shortest_double(low) + ", " + shortest_double(high) + "]";
  }
  if (std::isfinite(low)) return ">= " + shortest_double(low);
  if (std::isfinite(high)) return "<= " + shortest_double(high);
  return "";
}

MetricRange metric_range(const std::string& name) {
  const std::string base = metric_base(name);
  if (base == "r2") return {-std::numeric_limits<double>::infinity(), 1.0};
  if (name == kOlderValidationMse) return {0.0, std::numeric_limits<double>::infinity()};
  for (const auto& m : base_metrics()) {
    if (m == base) return {0.0, std::numeric_limits<double>::infinity()};
  }
  return {};
}

}  // namespace cnclab
