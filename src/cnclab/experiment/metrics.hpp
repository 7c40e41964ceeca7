#pragma once
// Regression metrics over test predictions and targets in physical units
// (one sample per column; all outputs pooled).
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace cnclab {

// Names accepted in an experiment's `metrics:` list.
const std::vector<std::string>& known_metrics();

// mse   = mean (ŷ − y)²            rmse = √mse
// mae   = mean |ŷ − y|             max_abs_error = max |ŷ − y|
// r2    = 1 − Σ(ŷ − y)² / Σ(y − ȳ)²  (per output row, averaged over rows)
// Throws cnclab::Error on a name not in known_metrics() or mismatched shapes.
std::map<std::string, double> regression_metrics(const Eigen::MatrixXd& predictions,
                                                 const Eigen::MatrixXd& targets,
                                                 const std::vector<std::string>& names);

// Summary of a sample of non-negative errors (tool-tip distances, ...).
struct ErrorSummary {
  std::size_t count = 0;
  double mean = 0, p95 = 0, max = 0;  // NaN when count = 0
};
// p95: linear interpolation between order statistics at rank 0.95 (n - 1)
// (numpy's default 'linear' percentile). Throws cnclab::Error on a NaN.
ErrorSummary summarize_errors(std::vector<double> errors);

// A metric or loss for people to read: 6 significant digits ("%.6g").
std::string format_metric(double value);

}  // namespace cnclab
