#include "cnclab/studies/contour_error/narx_metrics.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/motion/contour_error.hpp"

namespace cnclab {
namespace {

constexpr double kNoValue = std::numeric_limits<double>::quiet_NaN();
const char* const kAxes[] = {"x", "y"};
const char* const kEstimates[] = {"taylor", "tangent", "osculating"};

int axis_index(const std::string& axis) {
  return axis == "x" ? 0 : axis == "y" ? 1 : -1;
}

std::vector<std::string> metric_names() {
  std::vector<std::string> names;
  for (const char* a : kAxes) {
    for (const char* m : {"closed_loop_rms_", "closed_loop_max_", "zero_rms_", "zero_max_"}) {
      names.push_back(std::string(m) + a);
    }
  }
  for (const char* m :
       {"stable", "contour_rms", "contour_max", "exact_contour_mean", "exact_contour_max"}) {
    names.emplace_back(m);
  }
  for (const char* e : kEstimates) {
    names.push_back(std::string(e) + "_mean_abs_diff");
    names.push_back(std::string(e) + "_max_abs_diff");
  }
  return names;
}

// A metadata column over the scored steps: the validation part from its
// first predicted step (first_step), the steps the closed-loop metrics cover.
Eigen::VectorXd scored_row(const SequencePrediction& p, const std::string& name) {
  const Dataset& d = *p.data;
  const Eigen::Index row = d.metadata_row(name);
  if (row < 0) throw Error("contour_error metrics: the dataset has no metadata column " + name);
  const Eigen::Index first = static_cast<Eigen::Index>(p.first_validation) + p.first_step;
  return d.metadata.row(row).segment(first, d.metadata.cols() - first).transpose();
}

// The dataset-level numbers over the scored steps: zero predictor, exact
// contour, estimates.
void dataset_metrics(const SequencePrediction& p, std::map<std::string, double>& out) {
  for (const char* a : kAxes) {
    const Eigen::VectorXd e = scored_row(p, std::string("e_ref_") + a);
    out[std::string("zero_rms_") + a] = std::sqrt(e.squaredNorm() / static_cast<double>(e.size()));
    out[std::string("zero_max_") + a] = e.cwiseAbs().maxCoeff();
  }
  const Eigen::VectorXd exact = scored_row(p, "contour_exact");
  out["exact_contour_mean"] = exact.mean();
  out["exact_contour_max"] = exact.maxCoeff();
  for (const char* m : kEstimates) {
    const Eigen::ArrayXd diff = (scored_row(p, std::string("contour_") + m) - exact).array().abs();
    out[std::string(m) + "_mean_abs_diff"] = diff.mean();
    out[std::string(m) + "_max_abs_diff"] = diff.maxCoeff();
  }
}

// Per network: the prediction in µm (written to `um`) and its error against
// the measurement over the steps from first_step; NaN when unstable.
bool axis_metrics(const SequencePrediction& p, std::size_t a, const ColumnRange& r,
                  Eigen::VectorXd& um, std::map<std::string, double>& out) {
  const Dataset& d = *p.data;
  const auto half = static_cast<Eigen::Index>(p.first_validation);
  const Eigen::VectorXd& y = p.predicted[a];
  const Eigen::Index m = y.size(), first = p.first_step;
  um.resize(m);
  for (Eigen::Index t = 0; t < first; ++t) um[t] = to_physical(y[t], r);
  double sq = 0, mx = 0;
  bool stable = true;
  for (Eigen::Index t = first; t < m; ++t) {
    if (!std::isfinite(y[t]) || std::abs(y[t]) > kStableBound) stable = false;
    um[t] = to_physical(y[t], r);
    const double diff = um[t] - to_physical(d.targets(p.target_rows[a], half + t), r);
    sq += diff * diff;
    mx = std::max(mx, std::abs(diff));
  }
  out["closed_loop_rms_" + p.axes[a]] =
      stable ? std::sqrt(sq / static_cast<double>(m - first)) : kNoValue;
  out["closed_loop_max_" + p.axes[a]] = stable ? mx : kNoValue;
  return stable;
}

// Taylor contour error (Eqs. 3-6) from the predicted following errors `um`
// (x, y order) against the exact contour error of the data.
void contour_metrics(const SequencePrediction& p, const std::vector<Eigen::VectorXd>& um,
                     std::map<std::string, double>& out) {
  const Dataset& d = *p.data;
  const auto row = [&](const char* name) { return d.metadata_row(name); };
  const Eigen::Index rx = row("ref_x"), ry = row("ref_y"), d1x = row("d1_x"), d1y = row("d1_y"),
                     d2x = row("d2_x"), d2y = row("d2_y"), ex = row("contour_exact");
  const auto half = static_cast<Eigen::Index>(p.first_validation);
  const Eigen::Index m = um[0].size(), first = p.first_step;
  double sq = 0, mx = 0;
  for (Eigen::Index t = first; t < m; ++t) {
    const Eigen::Index k = half + t;
    PathPoint pp;
    pp.position = {d.metadata(rx, k), d.metadata(ry, k)};
    pp.d1 = {d.metadata(d1x, k), d.metadata(d1y, k)};
    pp.d2 = {d.metadata(d2x, k), d.metadata(d2y, k)};
    const Vec2 e_mm = {um[0][t] / 1000.0, um[1][t] / 1000.0};
    const double c = std::abs(taylor_contour_error(pp, pp.position - e_mm)) * 1000.0;
    const double diff = c - d.metadata(ex, k);
    sq += diff * diff;
    mx = std::max(mx, std::abs(diff));
  }
  out["contour_rms"] = std::sqrt(sq / static_cast<double>(m - first));
  out["contour_max"] = mx;
}

std::map<std::string, double> compute(const SequencePrediction& p) {
  if (p.data == nullptr || p.data->generator != "following_error") {
    throw Error("contour_error metrics need a following_error dataset");
  }
  std::map<std::string, double> out;
  for (const auto& name : metric_names()) out[name] = kNoValue;
  dataset_metrics(p, out);
  const FollowingErrorRanges ranges = following_error_ranges(*p.data);
  std::vector<Eigen::VectorXd> um(2);
  std::vector<bool> have(2, false);
  bool stable = true;
  for (std::size_t a = 0; a < p.axes.size(); ++a) {
    const int i = axis_index(p.axes[a]);
    if (i < 0) throw Error("contour_error metrics: axis '" + p.axes[a] + "' is neither x nor y");
    const auto u = static_cast<std::size_t>(i);
    stable = axis_metrics(p, a, ranges.following_error[u], um[u], out) && stable;
    have[u] = true;
  }
  out["stable"] = stable ? 1.0 : 0.0;
  if (stable && have[0] && have[1]) contour_metrics(p, um, out);
  return out;
}

}  // namespace

void register_contour_error_metrics() {
  // Every metric is a distance in µm but `stable`, a 0/1 flag.
  std::map<std::string, std::string> units;
  std::map<std::string, MetricRange> ranges;
  for (const auto& name : metric_names()) {
    units[name] = name == "stable" ? "1" : "µm";
    ranges[name] = {0.0, name == "stable" ? 1.0 : std::numeric_limits<double>::infinity()};
  }
  register_sequence_metrics({"contour_error (seed 002)", metric_names(), compute, units, ranges});
}

}  // namespace cnclab
