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

// A metric or loss for people to read: 6 significant digits ("%.6g").
std::string format_metric(double value);

}  // namespace cnclab
