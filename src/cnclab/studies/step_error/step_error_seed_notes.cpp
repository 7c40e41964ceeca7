#include "cnclab/studies/step_error/step_error_seed_notes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {

// "(5 and 5 seeds; Welch p = 0.00012 < 0.05)"
std::string seed_notes_test(const SeedComparison& c, double alpha) {
  const std::string seeds = std::to_string(c.a.n) + " and " + std::to_string(c.b.n) + " seeds; ";
  if (std::isnan(c.welch.p_value)) return "(" + seeds + "Welch's test undefined: no spread)";
  char p[32];
  std::snprintf(p, sizeof p, "%.2g", c.welch.p_value);
  char a[32];
  std::snprintf(a, sizeof a, "%g", alpha);
  return "(" + seeds + "Welch p = " + p + (c.significant ? " < " : " ≥ ") + a + ")";
}

}  // namespace

std::string seed_mean_std_text(const SampleSummary& s, int decimals) {
  if (s.n < 2) return fixed_decimals(s.mean, decimals) + " (1 seed)";
  return fixed_decimals(s.mean, decimals) + " ± " + fixed_decimals(s.std, decimals);
}

SeedComparison compare_seeds(const SeedSample& a, const SeedSample& b, double alpha) {
  SeedComparison c;
  c.a = summarize(a.values);
  c.b = summarize(b.values);
  c.welch = welch_t_test(a.values, b.values);
  c.significant = !std::isnan(c.welch.p_value) && c.welch.p_value < alpha;
  return c;
}

std::string seed_difference_sentence(const std::string& what, const SeedSample& a,
                                     const SeedSample& b, int decimals, double alpha) {
  const SeedComparison c = compare_seeds(a, b, alpha);
  const std::string left = a.label + " " + seed_mean_std_text(c.a, decimals);
  const std::string right = b.label + " " + seed_mean_std_text(c.b, decimals);
  if (!c.significant) {
    return what + ": " + left + " and " + right + " are not distinguishable from seed noise " +
           seed_notes_test(c, alpha) + ".";
  }
  const char* order = c.a.mean < c.b.mean ? " is lower than " : " is higher than ";
  return what + ": " + left + order + right + " " + seed_notes_test(c, alpha) + ".";
}

std::string lowest_mean_sentence(const std::string& what, const std::vector<SeedSample>& samples,
                                 int decimals, double alpha) {
  std::vector<const SeedSample*> ranked;
  for (const auto& s : samples) {
    if (s.values.size() >= 2) ranked.push_back(&s);
  }
  if (ranked.size() < 2) return "";
  const auto mean = [](const SeedSample* s) { return summarize(s->values).mean; };
  std::stable_sort(ranked.begin(), ranked.end(),
                   [&](const SeedSample* x, const SeedSample* y) { return mean(x) < mean(y); });
  const SeedComparison c = compare_seeds(*ranked[0], *ranked[1], alpha);
  const std::string best = ranked[0]->label + " (" + seed_mean_std_text(c.a, decimals) + ")";
  const std::string next = ranked[1]->label + " (" + seed_mean_std_text(c.b, decimals) + ")";
  if (c.significant) {
    return what + ": lowest mean at " + best + ", below the next, " + next +
           ", beyond seed noise " + seed_notes_test(c, alpha) + ": " + ranked[0]->label +
           " is the best.";
  }
  return what + ": lowest mean at " + best + ", but not distinguishable from the next, " + next +
         ", by seed noise " + seed_notes_test(c, alpha) + ": no single best " +
         "setting is supported.";
}

}  // namespace cnclab
