"""scipy's numbers for tests/report/statistics_test.cpp: Welch's t-test
(scipy.stats.ttest_ind(b, a, equal_var=False): t of mean(b) - mean(a)) and
the 95 % Student-t interval of each group's mean
(scipy.stats.t.interval(0.95, n - 1, mean, sem)) on fixed data, printed
with 17 significant digits as C++ initialisers.

Usage: /usr/bin/python3 tests/report/welch_reference.py   (scipy 1.10, Debian 12)
"""
import numpy as np
import scipy
from scipy import stats

# (name, a, b): equal sizes; unequal sizes and spreads; a large difference
# (small p); two values in one group.
CASES = [
    ("equal_sizes", [0.82, 0.91, 0.77, 0.88, 0.95], [0.71, 0.69, 0.80, 0.74, 0.66]),
    ("unequal", [5.81, 6.02, 5.33, 6.44, 5.47], [6.58, 7.91, 5.12, 6.10, 7.40, 6.95, 5.88]),
    ("small_p", [1.0, 1.1, 0.9, 1.05, 0.95, 1.02], [2.0, 2.3, 1.8, 2.1, 2.2]),
    ("two_values", [3.0, 3.5], [2.0, 2.2, 2.1, 2.6]),
]


def g(x):
    return f"{x:.17g}"


print(f"// scipy {scipy.__version__}")
for name, a, b in CASES:
    a, b = np.array(a), np.array(b)
    r = stats.ttest_ind(b, a, equal_var=False)
    va, vb = a.var(ddof=1) / len(a), b.var(ddof=1) / len(b)
    df = (va + vb) ** 2 / (va**2 / (len(a) - 1) + vb**2 / (len(b) - 1))
    ci = []
    for x in (a, b):
        lo, hi = stats.t.interval(0.95, len(x) - 1, loc=x.mean(), scale=stats.sem(x))
        ci += [lo, hi]
    print(f"{{\"{name}\", {g(r.statistic)}, {g(df)}, {g(r.pvalue)}, "
          f"{g(ci[0])}, {g(ci[1])}, {g(ci[2])}, {g(ci[3])}}},")
# Student t quantiles and CDF values at fractional df (Welch's df is not whole).
for p, df in [(0.975, 4.0), (0.975, 7.3), (0.6, 30.0)]:
    print(f"{{{g(p)}, {g(df)}, {g(stats.t.ppf(p, df))}}},")
for t, df in [(-2.1, 4.0), (0.3, 7.3), (3.7, 2.5), (-0.05, 100.0)]:
    print(f"{{{g(t)}, {g(df)}, {g(stats.t.cdf(t, df))}}},")
# A far-tail quantile at fractional df to 40 digits with mpmath: scipy's
# t.ppf(0.995, 2.5) = 7.16372813402124 is 4.9e-9 off there (Boost.Math: 2e-15),
# so the C++ test compares this one with mpmath instead.
import mpmath

mpmath.mp.dps = 40
df = mpmath.mpf(2.5)


def t_cdf(t):
    return 1 - mpmath.betainc(df / 2, mpmath.mpf(1) / 2, 0, df / (df + t * t), regularized=True) / 2


print(f"// mpmath: t.ppf(0.995, 2.5) = {mpmath.nstr(mpmath.findroot(lambda t: t_cdf(t) - mpmath.mpf('0.995'), 7.16), 20)}")
