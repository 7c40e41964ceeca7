#pragma once
// The values a metric can take, so that an interval over repeats (report/
// compare_groups.hpp) never claims an impossible one: a Student-t interval
// of a mean r2 of 0.97 ± 0.1 would reach 1.07, one of a small MAE below 0.
#include <limits>
#include <string>

namespace cnclab {

struct MetricRange {
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  bool bounded() const;      // a finite low or high
  std::string text() const;  // ">= 0", "<= 1", "in [0, 1]", "" when unbounded
};

// The range of a metric of metrics.hpp (base_metrics()), also with a split
// prefix ("validation.rmse" as "rmse"):
//   mse, rmse, mae, max_abs_error, normalised_mse, normalised_validation_mse   >= 0
//   r2 = 1 − SSE/SST                                                           <= 1
// Unbounded for another name.
MetricRange metric_range(const std::string& name);

}  // namespace cnclab
