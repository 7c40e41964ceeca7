#pragma once
// Error statistics of a step-error test set, as seed 000 reports them
// (Tables 3, 6, 7 and the text of "Predict step error values of Surface
// 2/3"): absolute error |y - t| in µm, relative error 100 |y - t| / |t| in %,
// counts in bins and shares below thresholds.
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "cnclab/report/typed_table.hpp"

namespace cnclab {

// Counts of values in half-open bins [edges[k], edges[k+1]); the paper's
// "< 0.1" is [0, 0.1), "0.1-0.2" is [0.1, 0.2). Values at or above the last
// edge go to `above` (the paper's tables stop at 0.8 µm (Table 3) and 5 µm
// (Table 6) although Table 6's maximum is 5.25 µm); values below the first
// edge to `below`. NaN values are errors.
struct BinCounts {
  std::vector<double> edges;        // strictly increasing; the last may be +inf
  std::vector<std::size_t> counts;  // edges.size() - 1 bins
  std::size_t below = 0, above = 0;
  std::size_t total() const;  // all values counted, below and above included
};

// Throws Error when edges has fewer than 2 entries or is not strictly
// increasing, or a value is NaN.
BinCounts bin_counts(const std::vector<double>& values, const std::vector<double>& edges);

// 100 count / total; NaN when total is 0.
double percent(std::size_t count, std::size_t total);

// Labels for bins as the paper prints them: "< 0.1", "0.1–0.2", ..., "> 20"
// (an infinite last edge), and "≥ 0.8" for the overflow bin. `unit` is
// appended ("%" -> "< 1 %").
std::vector<std::string> bin_labels(const std::vector<double>& edges, const std::string& unit);
std::string overflow_label(const std::vector<double>& edges, const std::string& unit);
// The bin columns of a typed table (typed_table.hpp): headers bin_labels
// (and overflow_label when `overflow`) with `shown_unit`; csv/json names
// bin_<low>_<high>_<unit>, high "inf" for a last column that counts
// everything at or above an edge.
std::vector<TableColumn> bin_columns(const std::vector<double>& edges, const std::string& unit,
                                     const std::string& shown_unit, bool overflow);

// |predicted - target| per sample (same units as the inputs: µm here).
std::vector<double> absolute_errors(const std::vector<double>& predicted,
                                    const std::vector<double>& target);
// 100 |predicted - target| / |target| per sample [%]; +inf where the target
// is 0 and the prediction is not.
std::vector<double> relative_errors_percent(const std::vector<double>& predicted,
                                            const std::vector<double>& target);

// The scalar figures the paper's text quotes for a test set.
struct ErrorFigures {
  std::size_t samples = 0;
  double max_abs = std::numeric_limits<double>::quiet_NaN();   // µm
  double mean_abs = std::numeric_limits<double>::quiet_NaN();  // µm
  // Shares [%]: |e| < threshold (absolute, µm) or relative error < threshold (%).
  double share_abs_below(double threshold_um) const;
  double share_rel_below(double threshold_percent) const;

  std::vector<double> abs_um, rel_percent;  // per sample
};

ErrorFigures error_figures(const std::vector<double>& predicted, const std::vector<double>& target);

}  // namespace cnclab
