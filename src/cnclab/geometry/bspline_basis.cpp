#include "cnclab/geometry/bspline_basis.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {

void validate_knot_vector(const std::vector<double>& knots, int degree, std::size_t num_points,
                          const std::string& name) {
  if (degree < 1 || degree > kMaxBsplineDegree) {
    throw OptionError(name + " degree", std::to_string(degree),
                      "must be in [1, " + std::to_string(kMaxBsplineDegree) + "]");
  }
  const auto p = static_cast<std::size_t>(degree);
  if (num_points < p + 1) {
    throw OptionError(name + " control points", std::to_string(num_points),
                      "a degree-" + std::to_string(degree) + " direction needs at least " +
                          std::to_string(p + 1) + " control points");
  }
  if (knots.size() != num_points + p + 1) {
    throw OptionError(name + " knots", std::to_string(knots.size()) + " values",
                      "must have (control points + degree + 1) = " +
                          std::to_string(num_points + p + 1) + " values");
  }
  for (std::size_t i = 0; i < knots.size(); ++i) {
    if (!std::isfinite(knots[i])) {
      throw OptionError(name + " knots",
                        "[" + std::to_string(i) + "] = " + std::to_string(knots[i]),
                        "knots must be finite");
    }
    if (i > 0 && knots[i] < knots[i - 1]) {
      throw OptionError(name + " knots",
                        "[" + std::to_string(i) + "] = " + shortest_double(knots[i]) + " < [" +
                            std::to_string(i - 1) + "] = " + shortest_double(knots[i - 1]),
                        "the knot vector must be non-decreasing");
    }
  }
  for (std::size_t i = 1; i <= p; ++i) {
    if (knots[i] != knots[0] || knots[knots.size() - 1 - i] != knots.back()) {
      throw OptionError(name + " knots", "first/last " + std::to_string(p + 1) + " values",
                        "must be equal (clamped knot vector: the curve starts and ends at its "
                        "end control points)");
    }
  }
  if (!(knots.back() > knots.front())) {
    throw OptionError(name + " knots",
                      shortest_double(knots.front()) + ".." + shortest_double(knots.back()),
                      "the parameter range must be non-empty");
  }
  // Interior multiplicity <= degree keeps the curve continuous (C^(p-m)).
  std::size_t run = 1;
  for (std::size_t i = p + 1; i + p + 1 < knots.size(); ++i) {
    run = (knots[i] == knots[i - 1] && i > p + 1) ? run + 1 : 1;
    if (run > p) {
      throw OptionError(
          name + " knots", shortest_double(knots[i]),
          "an interior knot may repeat at most degree = " + std::to_string(degree) + " times");
    }
  }
}

int find_span(std::span<const double> knots, int degree, double t) {
  const int n = static_cast<int>(knots.size()) - degree - 2;
  const auto k = [&](int i) { return knots[i]; };
  if (t >= k(n + 1)) return n;
  if (t <= k(degree)) return degree;
  // Binary search (A2.1) for knots[mid] <= t < knots[mid+1].
  int low = degree, high = n + 1;
  int mid = (low + high) / 2;
  while (t < k(mid) || t >= k(mid + 1)) {
    if (t < k(mid)) {
      high = mid;
    } else {
      low = mid;
    }
    mid = (low + high) / 2;
  }
  return mid;
}

void basis_derivatives(std::span<const double> knots, int degree, int span, double t, int order,
                       BasisDerivatives& ders) {
  // Plain int indices below: A2.3 as printed (sizes are bounded by
  // kMaxBsplineDegree, checked by validate_knot_vector).
  const int p = degree;
  constexpr int kSize = kMaxBsplineDegree + 1;
  // ndu[j][r]: basis functions (upper triangle incl. diagonal) and knot
  // differences (lower triangle).
  double ndu[kSize][kSize];
  double left[kSize], right[kSize];
  ndu[0][0] = 1.0;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0.0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  for (int j = 0; j <= p; ++j) ders[0][j] = ndu[j][p];
  for (int k = 1; k <= order; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] = 0.0;
  }
  const int n = std::min(order, p);
  double a[2][kSize];
  for (int r = 0; r <= p; ++r) {
    int s1 = 0, s2 = 1;
    a[0][0] = 1.0;
    for (int k = 1; k <= n; ++k) {
      double d = 0.0;
      const int rk = r - k, pk = p - k;
      if (r >= k) {
        a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
        d = a[s2][0] * ndu[rk][pk];
      }
      const int j1 = rk >= -1 ? 1 : -rk;
      const int j2 = (r - 1 <= pk) ? k - 1 : p - r;
      for (int j = j1; j <= j2; ++j) {
        a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][rk + j];
        d += a[s2][j] * ndu[rk + j][pk];
      }
      if (r <= pk) {
        a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
        d += a[s2][k] * ndu[r][pk];
      }
      ders[k][r] = d;
      std::swap(s1, s2);
    }
  }
  // Multiply by p!/(p-k)!.
  double factor = p;
  for (int k = 1; k <= n; ++k) {
    for (int j = 0; j <= p; ++j) ders[k][j] *= factor;
    factor *= (p - k);
  }
}

}  // namespace cnclab
