"""scipy's numbers for the paired tests and the strata of `compare --group-by`
(tests/report/statistics_test.cpp, tests/report/compare_groups_test.cpp),
printed with 17 significant digits as C++ initialisers.

- Paired t-test: scipy.stats.ttest_rel(b, a) (t of mean(b - a)).
- Wilcoxon signed-rank: scipy.stats.wilcoxon(b, a) (statistic min(W+, W-),
  two-sided p). Without ties and zeros at n <= 50 scipy's default is the
  exact distribution; with ties we compare with method="approx" (scipy's
  default would truncate the half ranks in its exact table); with zero
  differences, with the zeros removed first (scipy would switch to the
  approximation; dropping them is zero_method "wilcox", and the exact
  distribution holds for the rest).
- Strata: a 2 (dropout) x 2 (learning rate) x 4 seeds design grouped by
  dropout: per learning rate, Welch's t-test (ttest_ind(b, a,
  equal_var=False)), the paired t-test and Wilcoxon over the seeds; and the
  Welch test pooled over the learning rates.

Usage: /usr/bin/python3 tests/report/paired_reference.py   (scipy 1.10, Debian 12)
"""
import warnings

import numpy as np
import scipy
from scipy import stats

warnings.simplefilter("ignore")  # "sample size too small for normal approximation": intended


def g(x):
    return f"{x:.17g}"


# (name, a, b, method): no ties (exact); ties (approx); zeros (removed, exact);
# 60 pairs (approximation: n > 50).
rng = np.random.default_rng(7)
big_a = np.round(rng.normal(1.0, 0.1, 60), 6)
big_b = np.round(big_a + rng.normal(0.02, 0.05, 60), 6)
CASES = [
    ("exact5", [0.81, 0.92, 0.77, 0.88, 0.95], [0.71, 0.95, 0.70, 0.74, 0.66], "exact"),
    ("exact8", [5.1, 4.8, 6.0, 5.5, 5.9, 4.7, 5.3, 6.2],
     [5.6, 5.0, 6.15, 6.35, 5.8, 5.4, 5.95, 7.15], "exact"),
    ("ties", [1.0, 2.0, 3.0, 4.0, 5.0, 6.0], [1.5, 2.5, 2.5, 4.25, 5.75, 6.5], "approx"),
    ("zeros", [1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0], [1.0, 2.3, 2.6, 4.0, 5.9, 6.8, 8.1], "nonzero"),
    ("n60", list(big_a), list(big_b), "approx"),
]

print(f"// scipy {scipy.__version__}")
print("// paired: {name, t, df, p, wilcoxon_w, wilcoxon_p}")
for name, a, b, method in CASES:
    a, b = np.array(a), np.array(b)
    t = stats.ttest_rel(b, a)
    d = b - a
    if method == "exact":  # scipy's exact table holds only without ties and zeros
        assert len(set(np.abs(d))) == len(d) and np.all(d != 0), name
    if method == "nonzero":
        keep = (b - a) != 0
        w = stats.wilcoxon(b[keep], a[keep])
    else:
        w = stats.wilcoxon(b, a, method=method)
    print(f"{{\"{name}\", {g(t.statistic)}, {len(a) - 1}, {g(t.pvalue)}, {g(w.statistic)}, "
          f"{g(w.pvalue)}}},")
print("// the 60 pairs:")
print("// a = {" + ", ".join(repr(float(x)) for x in big_a) + "}")
print("// b = {" + ", ".join(repr(float(x)) for x in big_b) + "}")

# Strata: mse[dropout][learning rate] over seeds 1..4.
MSE = {
    ("0.5", "0.001"): [2.10, 2.35, 1.98, 2.22],
    ("1.0", "0.001"): [1.71, 2.05, 1.80, 1.77],
    ("0.5", "0.01"): [0.91, 1.02, 0.88, 0.97],
    ("1.0", "0.01"): [0.95, 1.01, 0.79, 0.99],
}
print("// strata: {learning_rate, welch_t, welch_df, welch_p, paired_t, paired_p, wilcoxon_w, "
      "wilcoxon_p}")
for lr in ("0.001", "0.01"):
    a, b = np.array(MSE[("0.5", lr)]), np.array(MSE[("1.0", lr)])
    welch = stats.ttest_ind(b, a, equal_var=False)
    va, vb = a.var(ddof=1) / len(a), b.var(ddof=1) / len(b)
    df = (va + vb) ** 2 / (va**2 / (len(a) - 1) + vb**2 / (len(b) - 1))
    paired = stats.ttest_rel(b, a)
    w = stats.wilcoxon(b, a)
    print(f"{{\"{lr}\", {g(welch.statistic)}, {g(df)}, {g(welch.pvalue)}, {g(paired.statistic)}, "
          f"{g(paired.pvalue)}, {g(w.statistic)}, {g(w.pvalue)}}},")
a = np.array(MSE[("0.5", "0.001")] + MSE[("0.5", "0.01")])
b = np.array(MSE[("1.0", "0.001")] + MSE[("1.0", "0.01")])
pooled = stats.ttest_ind(b, a, equal_var=False)
paired = stats.ttest_rel(b, a)  # pairs: same seed and learning rate
print(f"// pooled over the learning rate: welch_t {g(pooled.statistic)}, p {g(pooled.pvalue)}; "
      f"paired_t {g(paired.statistic)}, p {g(paired.pvalue)}")
