#include "cnclab/studies/step_error/step_error_stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

std::size_t BinCounts::total() const {
  std::size_t n = below + above;
  for (std::size_t c : counts) n += c;
  return n;
}

BinCounts bin_counts(const std::vector<double>& values, const std::vector<double>& edges) {
  if (edges.size() < 2) throw Error("bin_counts: need at least 2 edges");
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    if (!(edges[k] < edges[k + 1])) {
      throw Error("bin_counts: edges must be strictly increasing (edge " + std::to_string(k) +
                  " = " + shortest_double(edges[k]) + ", next " + shortest_double(edges[k + 1]) +
                  ")");
    }
  }
  BinCounts b;
  b.edges = edges;
  b.counts.assign(edges.size() - 1, 0);
  for (double v : values) {
    if (std::isnan(v)) throw Error("bin_counts: NaN value");
    if (v < edges.front()) {
      ++b.below;
    } else if (v >= edges.back()) {
      ++b.above;
    } else {
      // The first edge greater than v closes v's bin [edges[k], edges[k+1]).
      const auto k = std::upper_bound(edges.begin(), edges.end(), v) - edges.begin() - 1;
      ++b.counts[static_cast<std::size_t>(k)];
    }
  }
  return b;
}

double percent(std::size_t count, std::size_t total) {
  return total == 0 ? std::nan("")
                    : 100.0 * static_cast<double>(count) / static_cast<double>(total);
}

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

std::string with_unit(const std::string& text, const std::string& unit) {
  return unit.empty() ? text : text + " " + unit;
}

}  // namespace

std::vector<std::string> bin_labels(const std::vector<double>& edges, const std::string& unit) {
  std::vector<std::string> labels;
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    if (k == 0 && edges[0] == 0.0) {
      labels.push_back(with_unit("< " + number(edges[1]), unit));
    } else if (std::isinf(edges[k + 1])) {
      labels.push_back(with_unit("> " + number(edges[k]), unit));
    } else {
      labels.push_back(with_unit(number(edges[k]) + "–" + number(edges[k + 1]), unit));
    }
  }
  return labels;
}

std::string overflow_label(const std::vector<double>& edges, const std::string& unit) {
  return with_unit("≥ " + number(edges.back()), unit);
}

std::vector<TableColumn> bin_columns(const std::vector<double>& edges, const std::string& unit,
                                     const std::string& shown_unit, bool overflow) {
  const std::vector<std::string> labels = bin_labels(edges, shown_unit);
  std::vector<TableColumn> columns;
  // Appended, not `"bin_" + std::string`: GCC 12 warns falsely (-Wrestrict, PR105329).
  const auto name = [](double low, double high) {
    std::string n = "bin_";
    n += shortest_double(low);
    n += "_";
    n += std::isinf(high) ? std::string("inf") : shortest_double(high);
    return n;
  };
  for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
    columns.push_back(number_column(labels[k], name(edges[k], edges[k + 1]), unit));
  }
  if (overflow) {
    columns.push_back(
        number_column(overflow_label(edges, shown_unit), name(edges.back(), HUGE_VAL), unit));
  }
  return columns;
}

std::vector<double> absolute_errors(const std::vector<double>& predicted,
                                    const std::vector<double>& target) {
  if (predicted.size() != target.size()) {
    throw Error("absolute_errors: " + std::to_string(predicted.size()) + " predictions for " +
                std::to_string(target.size()) + " targets");
  }
  std::vector<double> e(predicted.size());
  for (std::size_t i = 0; i < e.size(); ++i) e[i] = std::abs(predicted[i] - target[i]);
  return e;
}

std::vector<double> relative_errors_percent(const std::vector<double>& predicted,
                                            const std::vector<double>& target) {
  std::vector<double> e = absolute_errors(predicted, target);
  for (std::size_t i = 0; i < e.size(); ++i) {
    const double t = std::abs(target[i]);
    e[i] = e[i] == 0.0 ? 0.0 : t == 0.0 ? INFINITY : 100.0 * e[i] / t;
  }
  return e;
}

double ErrorFigures::share_abs_below(double threshold_um) const {
  const auto n =
      std::count_if(abs_um.begin(), abs_um.end(), [&](double e) { return e < threshold_um; });
  return percent(static_cast<std::size_t>(n), abs_um.size());
}

double ErrorFigures::share_rel_below(double threshold_percent) const {
  const auto n = std::count_if(rel_percent.begin(), rel_percent.end(),
                               [&](double e) { return e < threshold_percent; });
  return percent(static_cast<std::size_t>(n), rel_percent.size());
}

ErrorFigures error_figures(const std::vector<double>& predicted,
                           const std::vector<double>& target) {
  ErrorFigures f;
  f.abs_um = absolute_errors(predicted, target);
  f.rel_percent = relative_errors_percent(predicted, target);
  f.samples = f.abs_um.size();
  if (f.samples > 0) {
    f.max_abs = *std::max_element(f.abs_um.begin(), f.abs_um.end());
    double sum = 0;
    for (double e : f.abs_um) sum += e;
    f.mean_abs = sum / static_cast<double>(f.samples);
  }
  return f;
}

}  // namespace cnclab
