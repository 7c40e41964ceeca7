#include "cnclab/experiment/metrics.hpp"

#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"

namespace cnclab {

const std::vector<std::string>& known_metrics() {
  static const std::vector<std::string> names = {"mse", "rmse", "mae", "max_abs_error", "r2"};
  return names;
}

std::map<std::string, double> regression_metrics(const Eigen::MatrixXd& predictions,
                                                 const Eigen::MatrixXd& targets,
                                                 const std::vector<std::string>& names) {
  if (predictions.rows() != targets.rows() || predictions.cols() != targets.cols()) {
    throw Error("metrics: predictions are " + std::to_string(predictions.rows()) + "x" +
                std::to_string(predictions.cols()) + " but targets " +
                std::to_string(targets.rows()) + "x" + std::to_string(targets.cols()));
  }
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

std::string format_metric(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  return buf;
}

}  // namespace cnclab
