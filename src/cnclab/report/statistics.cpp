#include "cnclab/report/statistics.hpp"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <string>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"

namespace cnclab {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double mean_of(const std::vector<double>& x) {
  double sum = 0;
  for (double v : x) sum += v;
  return sum / static_cast<double>(x.size());
}

// Sample variance (n - 1), two-pass: exact for a constant sample.
double variance_of(const std::vector<double>& x, double mean) {
  double sq = 0;
  for (double v : x) sq += (v - mean) * (v - mean);
  return sq / static_cast<double>(x.size() - 1);
}

}  // namespace

double student_t_cdf(double t, double df) {
  if (!(df > 0) || std::isnan(t)) return kNaN;
  if (std::isinf(t)) return t > 0 ? 1.0 : 0.0;
  return boost::math::cdf(boost::math::students_t_distribution<double>(df), t);
}

double student_t_quantile(double p, double df) {
  if (!(df > 0) || !(p > 0 && p < 1)) return kNaN;
  return boost::math::quantile(boost::math::students_t_distribution<double>(df), p);
}

SampleSummary summarize(const std::vector<double>& x, double level) {
  SampleSummary s;
  s.n = x.size();
  if (x.empty()) {
    s.mean = s.std = s.ci_low = s.ci_high = kNaN;
    return s;
  }
  s.mean = mean_of(x);
  if (x.size() < 2) {
    s.std = s.ci_low = s.ci_high = kNaN;
    return s;
  }
  s.std = std::sqrt(variance_of(x, s.mean));
  const double df = static_cast<double>(x.size() - 1);
  const double half =
      student_t_quantile(0.5 * (1 + level), df) * s.std / std::sqrt(static_cast<double>(x.size()));
  s.ci_low = s.mean - half;
  s.ci_high = s.mean + half;
  return s;
}

WelchTest welch_t_test(const std::vector<double>& a, const std::vector<double>& b) {
  WelchTest w;
  w.difference = a.empty() || b.empty() ? kNaN : mean_of(b) - mean_of(a);
  w.t = w.df = w.p_value = kNaN;
  if (a.size() < 2 || b.size() < 2) return w;
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  const double va = variance_of(a, mean_of(a)) / na;  // s_a² / n_a
  const double vb = variance_of(b, mean_of(b)) / nb;
  const double se2 = va + vb;
  if (!(se2 > 0)) return w;
  w.t = w.difference / std::sqrt(se2);
  w.df = se2 * se2 / (va * va / (na - 1) + vb * vb / (nb - 1));
  // 2 (1 - F(|t|)) = 2 F(-|t|): the lower tail keeps precision for large |t|.
  w.p_value = 2 * student_t_cdf(-std::abs(w.t), w.df);
  return w;
}

void BootstrapOptions::validate() const {
  if (resamples < 100) {
    throw OptionError("resamples", std::to_string(resamples),
                      "must be at least 100 (percentile intervals need the tails)");
  }
  if (!(level > 0 && level < 1)) {
    throw OptionError("level", std::to_string(level), "must be in (0, 1)");
  }
}

double sorted_quantile(const std::vector<double>& sorted, double q) {
  if (sorted.empty()) return kNaN;
  const double pos = q * static_cast<double>(sorted.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(pos));
  const std::size_t hi = std::min(lo + 1, sorted.size() - 1);
  return sorted[lo] + (pos - static_cast<double>(lo)) * (sorted[hi] - sorted[lo]);
}

Interval bootstrap_difference_ci(const std::vector<double>& a, const std::vector<double>& b,
                                 const BootstrapOptions& options) {
  options.validate();
  if (a.empty() || b.empty()) return {kNaN, kNaN};
  Rng rng(options.seed, "bootstrap");
  const auto resampled_mean = [&](const std::vector<double>& x) {
    double sum = 0;
    for (std::size_t i = 0; i < x.size(); ++i) sum += x[rng.below(x.size())];
    return sum / static_cast<double>(x.size());
  };
  std::vector<double> diffs(options.resamples);
  for (double& d : diffs) {
    const double ma = resampled_mean(a);
    d = resampled_mean(b) - ma;
  }
  std::sort(diffs.begin(), diffs.end());
  const double tail = 0.5 * (1 - options.level);
  return {sorted_quantile(diffs, tail), sorted_quantile(diffs, 1 - tail)};
}

}  // namespace cnclab
