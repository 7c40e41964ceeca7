#include "cnclab/report/statistics.hpp"

#include <algorithm>
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
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

PairedTTest paired_t_test(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("paired_t_test: unequal sizes");
  PairedTTest r;
  r.pairs = a.size();
  std::vector<double> d(a.size());
  for (std::size_t i = 0; i < d.size(); ++i) d[i] = b[i] - a[i];
  r.difference = d.empty() ? kNaN : mean_of(d);
  r.df = d.size() < 2 ? kNaN : static_cast<double>(d.size() - 1);
  r.t = r.p_value = kNaN;
  if (d.size() < 2) return r;
  const double se = std::sqrt(variance_of(d, r.difference) / static_cast<double>(d.size()));
  if (!(se > 0)) return r;
  r.t = r.difference / se;
  r.p_value = 2 * student_t_cdf(-std::abs(r.t), r.df);
  return r;
}

namespace {

// P(W+ = w) for w = 0 .. n(n+1)/2 with n distinct ranks 1..n and independent
// fair signs: the number of subsets of {1..n} summing to w, over 2^n.
std::vector<double> signed_rank_distribution(std::size_t n) {
  std::vector<double> count(n * (n + 1) / 2 + 1, 0.0);
  count[0] = 1;
  for (std::size_t k = 1; k <= n; ++k) {
    for (std::size_t w = count.size() - 1; w >= k; --w) count[w] += count[w - k];
  }
  const double total = std::ldexp(1.0, static_cast<int>(n));
  for (double& c : count) c /= total;
  return count;
}

}  // namespace

WilcoxonTest wilcoxon_signed_rank(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("wilcoxon_signed_rank: unequal sizes");
  std::vector<double> d;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (b[i] - a[i] != 0) d.push_back(b[i] - a[i]);
  }
  WilcoxonTest r;
  r.n = d.size();
  if (d.empty()) {
    r.w = r.p_value = kNaN;
    return r;
  }
  // Average ranks of |d|, and the sizes of the groups of ties.
  std::vector<std::size_t> order(d.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t i, std::size_t j) { return std::abs(d[i]) < std::abs(d[j]); });
  std::vector<double> rank(d.size());
  double tie_term = 0;  // Σ (t³ - t)
  for (std::size_t lo = 0; lo < order.size();) {
    std::size_t hi = lo + 1;
    while (hi < order.size() && std::abs(d[order[hi]]) == std::abs(d[order[lo]])) ++hi;
    const double average = 0.5 * static_cast<double>(lo + 1 + hi);  // ranks lo+1 .. hi
    for (std::size_t k = lo; k < hi; ++k) rank[order[k]] = average;
    const double t = static_cast<double>(hi - lo);
    tie_term += t * t * t - t;
    lo = hi;
  }
  double plus = 0, minus = 0;
  for (std::size_t i = 0; i < d.size(); ++i) (d[i] > 0 ? plus : minus) += rank[i];
  r.w = std::min(plus, minus);
  const double n = static_cast<double>(d.size());
  if (d.size() <= 50 && tie_term == 0) {
    r.exact = true;
    const std::vector<double> pmf = signed_rank_distribution(d.size());
    const auto w = static_cast<std::size_t>(plus);  // whole without ties
    if (2 * w == pmf.size() - 1) {
      r.p_value = 1.0;  // the centre of the distribution
    } else {
      double below = 0, above = 0;
      for (std::size_t k = 0; k < pmf.size(); ++k) (k <= w ? below : above) += pmf[k];
      above += pmf[w];  // P(W+ >= w) includes w
      r.p_value = std::min(1.0, 2 * std::min(below, above));
    }
    return r;
  }
  const double mean = n * (n + 1) / 4;
  const double sd = std::sqrt(n * (n + 1) * (2 * n + 1) / 24 - tie_term / 48);
  const double z = (r.w - mean) / sd;
  r.p_value = 2 * boost::math::cdf(boost::math::normal_distribution<double>(), -std::abs(z));
  return r;
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
