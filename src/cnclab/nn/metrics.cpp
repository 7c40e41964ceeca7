#include "cnclab/nn/metrics.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"

namespace cnclab {

namespace {

void check_shapes(const Eigen::MatrixXd& predictions, const Eigen::MatrixXd& targets) {
  if (predictions.rows() != targets.rows() || predictions.cols() != targets.cols()) {
    throw Error("metrics: predictions are " + std::to_string(predictions.rows()) + "x" +
                std::to_string(predictions.cols()) + " but targets " +
                std::to_string(targets.rows()) + "x" + std::to_string(targets.cols()));
  }
}

bool contains(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

}  // namespace

const std::vector<std::string>& physical_metrics() {
  static const std::vector<std::string> names = {"mse", "rmse", "mae", "max_abs_error", "r2"};
  return names;
}

const std::vector<std::string>& normalised_metrics() {
  static const std::vector<std::string> names = {"normalised_mse", "normalised_validation_mse"};
  return names;
}

const std::vector<std::string>& known_metrics() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = physical_metrics();
    for (const auto& n : normalised_metrics()) all.push_back(n);
    return all;
  }();
  return names;
}

std::string metric_unit(const std::string& name, const std::vector<std::string>& target_units) {
  std::vector<std::string> units;
  for (const auto& u : target_units) {
    if (!contains(units, u)) units.push_back(u);
  }
  std::string u;
  for (const auto& x : units) u += (u.empty() ? "" : ", ") + x;
  if (units.size() > 1) u = "(" + u + ")";
  if (name == "mse") return u == "1" || u.empty() ? u : u + "²";
  if (name == "rmse" || name == "mae" || name == "max_abs_error") return u;
  if (name == "r2") return "1";
  if (contains(normalised_metrics(), name)) return "scaled²";
  return "";
}

double mean_squared_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  check_shapes(a, b);
  if (a.size() == 0) return NAN;
  return (a - b).array().square().sum() / static_cast<double>(a.size());
}

std::map<std::string, double> evaluation_metrics(const EvaluationData& d,
                                                 const std::vector<std::string>& names) {
  std::vector<std::string> physical;
  std::map<std::string, double> out;
  for (const auto& name : names) {
    if (name == "normalised_mse") {
      out[name] = mean_squared_error(d.test_outputs, d.test_scaled_targets);
    } else if (name == "normalised_validation_mse") {
      out[name] = mean_squared_error(d.validation_outputs, d.validation_scaled_targets);
    } else if (contains(physical_metrics(), name)) {
      physical.push_back(name);
    } else {
      throw Error("unknown metric '" + name + "'");
    }
  }
  out.merge(regression_metrics(d.test_predictions, d.test_targets, physical));
  return out;
}

std::map<std::string, double> regression_metrics(const Eigen::MatrixXd& predictions,
                                                 const Eigen::MatrixXd& targets,
                                                 const std::vector<std::string>& names) {
  check_shapes(predictions, targets);
  const Eigen::ArrayXXd err = (predictions - targets).array();
  const double n = static_cast<double>(err.size());
  std::map<std::string, double> out;
  for (const auto& name : names) {
    if (n == 0) {
      out[name] = NAN;
    } else if (name == "mse") {
      out[name] = err.square().sum() / n;
    } else if (name == "rmse") {
      out[name] = std::sqrt(err.square().sum() / n);
    } else if (name == "mae") {
      out[name] = err.abs().sum() / n;
    } else if (name == "max_abs_error") {
      out[name] = err.abs().maxCoeff();
    } else if (name == "r2") {
      double sum = 0;
      for (Eigen::Index r = 0; r < targets.rows(); ++r) {
        const double mean = targets.row(r).mean();
        const double ss_tot = (targets.row(r).array() - mean).square().sum();
        sum += 1.0 - err.row(r).square().sum() / ss_tot;
      }
      out[name] = sum / static_cast<double>(targets.rows());
    } else {
      throw Error("unknown metric '" + name + "'");
    }
  }
  return out;
}

ErrorSummary summarize_errors(std::vector<double> e) {
  ErrorSummary s;
  s.count = e.size();
  if (e.empty()) {
    s.mean = s.p95 = s.max = NAN;
    return s;
  }
  for (double v : e) {
    if (std::isnan(v))
      throw Error("error summary: NaN among " + std::to_string(e.size()) + " errors");
  }
  std::sort(e.begin(), e.end());
  double sum = 0;
  for (double v : e) sum += v;
  s.mean = sum / static_cast<double>(e.size());
  s.max = e.back();
  const double rank = 0.95 * static_cast<double>(e.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(rank));
  const std::size_t hi = std::min(lo + 1, e.size() - 1);
  s.p95 = e[lo] + (rank - static_cast<double>(lo)) * (e[hi] - e[lo]);
  return s;
}

std::string format_metric(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  return buf;
}

}  // namespace cnclab
