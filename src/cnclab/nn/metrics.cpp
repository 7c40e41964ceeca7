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

const std::vector<std::string>& metric_splits() {
  static const std::vector<std::string> names = {"train", "validation", "test"};
  return names;
}

const std::vector<std::string>& physical_metrics() {
  static const std::vector<std::string> names = {"mse", "rmse", "mae", "max_abs_error", "r2"};
  return names;
}

const std::vector<std::string>& base_metrics() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> all = physical_metrics();
    all.emplace_back("normalised_mse");
    return all;
  }();
  return names;
}

std::string metric_name(const std::string& split, const std::string& base) {
  return split + "." + base;
}

std::string metric_split(const std::string& name) {
  const auto dot = name.find('.');
  if (dot == std::string::npos) return "";
  const std::string split = name.substr(0, dot);
  return contains(metric_splits(), split) ? split : "";
}

std::string metric_base(const std::string& name) {
  const std::string split = metric_split(name);
  return split.empty() ? name : name.substr(split.size() + 1);
}

std::vector<std::string> metric_selection_names(const std::vector<std::string>& bases,
                                                const std::vector<std::string>& splits) {
  std::vector<std::string> names = bases;
  for (const auto& split : splits) {
    for (const auto& base : bases) names.push_back(metric_name(split, base));
  }
  if (bases == base_metrics()) names.emplace_back(kOlderValidationMse);
  return names;
}

std::vector<std::string> expand_metric_selection(const std::vector<std::string>& selection,
                                                 const std::vector<std::string>& bases,
                                                 const std::vector<std::string>& splits) {
  const std::vector<std::string> known = metric_selection_names(bases, splits);
  std::vector<std::string> out;
  const auto add = [&](const std::string& name) {
    if (!contains(out, name)) out.push_back(name);
  };
  for (const auto& entry : selection) {
    if (!contains(known, entry)) throw Error("unknown metric '" + entry + "'");
    if (entry == kOlderValidationMse) {
      add(metric_name("validation", "normalised_mse"));
    } else if (contains(bases, entry)) {
      for (const auto& split : splits) add(metric_name(split, entry));
    } else {
      add(entry);
    }
  }
  return out;
}

std::string metric_unit(const std::string& name, const std::vector<std::string>& target_units) {
  const std::string base = metric_base(name);
  std::vector<std::string> units;
  for (const auto& u : target_units) {
    if (!contains(units, u)) units.push_back(u);
  }
  std::string u;
  for (const auto& x : units) u += (u.empty() ? "" : ", ") + x;
  if (units.size() > 1) u = "(" + u + ")";
  if (base == "mse") return u == "1" || u.empty() ? u : u + "²";
  if (base == "rmse" || base == "mae" || base == "max_abs_error") return u;
  if (base == "r2") return "1";
  if (base == "normalised_mse") return "scaled²";
  return "";
}

double mean_squared_error(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  check_shapes(a, b);
  if (a.size() == 0) return NAN;
  return (a - b).array().square().sum() / static_cast<double>(a.size());
}

std::map<std::string, double> evaluation_metrics(const std::map<std::string, SplitData>& splits,
                                                 const std::vector<std::string>& names) {
  std::map<std::string, double> out;
  for (const auto& name : names) {
    const std::string split = metric_split(name), base = metric_base(name);
    if (split.empty() || !contains(base_metrics(), base)) {
      throw Error("unknown metric '" + name + "'");
    }
    const auto it = splits.find(split);
    if (it == splits.end() || it->second.targets.cols() == 0) continue;
    const SplitData& d = it->second;
    out[name] = base == "normalised_mse"
                    ? mean_squared_error(d.outputs, d.scaled_targets)
                    : regression_metrics(d.predictions, d.targets, {base}).at(base);
  }
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
