#pragma once
// Regression metrics of a trained network (one sample per column; all
// outputs pooled): test metrics in physical units, and MSEs in the
// normalised target units the network was trained in (test and validation
// split), which rank networks the way seed 004 Table 5 does.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace cnclab {

// Names accepted in an experiment's `metrics:` list: the physical ones and
// the normalised ones below.
const std::vector<std::string>& known_metrics();

// Test split, physical units (regression_metrics).
const std::vector<std::string>& physical_metrics();

// Normalised target units (targets through the experiment's target scaling s,
// fitted on the training split; network output f(x) taken as is):
//   normalised_mse             = mean over the test split of (f(x) − s(y))²
//   normalised_validation_mse  = the same over the validation split, of the
//                                returned weights (NaN without a validation split)
// Seed 004 Table 5's "MSE-test" and "MSE-validation".
const std::vector<std::string>& normalised_metrics();

// What evaluation_metrics needs; normalised matrices in the network's units.
struct EvaluationData {
  Eigen::MatrixXd test_predictions, test_targets;  // physical units
  Eigen::MatrixXd test_outputs, test_scaled_targets;
  Eigen::MatrixXd validation_outputs, validation_scaled_targets;
};

// Every metric in `names` (known_metrics()); cnclab::Error on another name.
std::map<std::string, double> evaluation_metrics(const EvaluationData& data,
                                                 const std::vector<std::string>& names);

// mean (a − b)² over all entries; NaN when empty; Error on mismatched shapes.
double mean_squared_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

// mse   = mean (ŷ − y)²            rmse = √mse
// mae   = mean |ŷ − y|             max_abs_error = max |ŷ − y|
// r2    = 1 − Σ(ŷ − y)² / Σ(y − ȳ)²  (per output row, averaged over rows)
// Throws cnclab::Error on a name not in physical_metrics() or mismatched shapes.
std::map<std::string, double> regression_metrics(const Eigen::MatrixXd& predictions,
                                                 const Eigen::MatrixXd& targets,
                                                 const std::vector<std::string>& names);

// The unit of a metric of known_metrics() for targets in `target_units`
// (one per output; the metrics pool all outputs). With u the targets' unit
// ("µm"; several different ones: "(mm, rad)"):
//   mse                          u²   (a lone "1" stays "1")
//   rmse, mae, max_abs_error     u
//   r2                           1    (dimensionless)
//   normalised_mse, normalised_validation_mse   "scaled²" (the network's scaled target units)
// "" for another name.
std::string metric_unit(const std::string& name, const std::vector<std::string>& target_units);

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
