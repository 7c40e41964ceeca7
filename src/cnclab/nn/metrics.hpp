#pragma once
// Regression metrics of a trained network (one sample per column; all
// outputs pooled), each on every split of the data.
//
// A stored metric is named "<split>.<base>" (metric_name):
//   split  train, validation, test                          (metric_splits())
//   base   mse, rmse, mae, max_abs_error, r2                (physical units)
//          normalised_mse                                   (the network's scaled units)
// e.g. validation.rmse, test.rmse, validation.normalised_mse. Validation is
// for choosing (sweep objectives, the tables' selections), test is reported
// once, after. Sequence models (model.type narx) name their registered
// metrics the same way, on the one split they have (experiment/spec.hpp,
// stored_metrics).
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace cnclab {

// train, validation, test.
const std::vector<std::string>& metric_splits();

// Physical units (regression_metrics).
const std::vector<std::string>& physical_metrics();

// physical_metrics() and normalised_mse: the mean over a split of
// (f(x) − s(y))², targets through the experiment's target scaling s (fitted on
// the training split), network output f(x) taken as is. Seed 004 Table 5's
// "MSE-test" and "MSE-validation" are test.normalised_mse and
// validation.normalised_mse.
const std::vector<std::string>& base_metrics();

// "<split>.<base>".
std::string metric_name(const std::string& split, const std::string& base);
// The split of a "<split>.<base>" name (one of metric_splits()); "" for a
// name without one.
std::string metric_split(const std::string& name);
// The base of a name ("rmse" of "test.rmse"); a name without a split itself.
std::string metric_base(const std::string& name);

// The older name of validation.normalised_mse, still accepted in `metrics:`
// and sweep objectives.
inline constexpr const char* kOlderValidationMse = "normalised_validation_mse";

// The names a `metrics:` list may hold, in order: each of `bases` (that
// metric on every split of `splits`), each "<split>.<base>" (that one only);
// with the mlp's bases also kOlderValidationMse.
std::vector<std::string> metric_selection_names(const std::vector<std::string>& bases,
                                                const std::vector<std::string>& splits);
// A `metrics:` list as the stored names, in the order given, each once.
// cnclab::Error naming the entry that is none of metric_selection_names.
std::vector<std::string> expand_metric_selection(const std::vector<std::string>& selection,
                                                 const std::vector<std::string>& bases,
                                                 const std::vector<std::string>& splits);

// One split's network outputs and targets.
struct SplitData {
  Eigen::MatrixXd predictions, targets;     // physical units
  Eigen::MatrixXd outputs, scaled_targets;  // the network's scaled target units
};

// Every metric in `names` ("<split>.<base>", base of base_metrics()) from
// `splits` (by split name). A split that is absent or has no samples has no
// metrics: its names are left out (a run without a validation split stores
// no validation.*). cnclab::Error on another name.
std::map<std::string, double> evaluation_metrics(const std::map<std::string, SplitData>& splits,
                                                 const std::vector<std::string>& names);

// mean (a − b)² over all entries; NaN when empty; Error on mismatched shapes.
double mean_squared_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b);

// mse   = mean (ŷ − y)²            rmse = √mse
// mae   = mean |ŷ − y|             max_abs_error = max |ŷ − y|
// r2    = 1 − Σ(ŷ − y)² / Σ(y − ȳ)²  (per output row, averaged over rows)
// Throws cnclab::Error on a name not in physical_metrics() or mismatched shapes.
// The names here are the bases (no split).
std::map<std::string, double> regression_metrics(const Eigen::MatrixXd& predictions,
                                                 const Eigen::MatrixXd& targets,
                                                 const std::vector<std::string>& names);

// The unit of a metric (its base, on any split: "test.rmse" as "rmse") for
// targets in `target_units` (one per output; the metrics pool all outputs).
// With u the targets' unit ("µm"; several different ones: "(mm, rad)"):
//   mse                          u²   (a lone "1" stays "1")
//   rmse, mae, max_abs_error     u
//   r2                           1    (dimensionless)
//   normalised_mse               "scaled²" (the network's scaled target units)
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
