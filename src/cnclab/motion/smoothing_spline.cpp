#include "cnclab/motion/smoothing_spline.hpp"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw Error("smoothing spline: " + what);
}

void check_inputs(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double p,
                  const Eigen::VectorXd& w) {
  std::ostringstream m;
  if (x.size() != y.size() || x.size() < 2) {
    m << "x (" << x.size() << ") and y (" << y.size() << ") must have the same length >= 2";
    fail(m.str());
  }
  if (!(p >= 0.0 && p <= 1.0)) {
    m << "p = " << p << ": must be in [0, 1]";
    fail(m.str());
  }
  if (w.size() != 0 && w.size() != x.size()) {
    m << "weights (" << w.size() << ") must be empty or as long as x (" << x.size() << ")";
    fail(m.str());
  }
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    if (!std::isfinite(x[i]) || !std::isfinite(y[i])) {
      m << "x[" << i << "] = " << x[i] << ", y[" << i << "] = " << y[i] << ": must be finite";
      fail(m.str());
    }
    if (i > 0 && !(x[i] > x[i - 1])) {
      m << "x[" << i << "] = " << x[i] << " <= x[" << i - 1 << "] = " << x[i - 1]
        << ": x must be strictly increasing";
      fail(m.str());
    }
    if (w.size() != 0 && !(w[i] > 0.0 && std::isfinite(w[i]))) {
      m << "weights[" << i << "] = " << w[i] << ": must be > 0 and finite";
      fail(m.str());
    }
  }
}

}  // namespace

SmoothingSpline SmoothingSpline::fit(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double p,
                                     const Eigen::VectorXd& weights) {
  check_inputs(x, y, p, weights);
  const Eigen::Index n = x.size();
  const Eigen::VectorXd w = weights.size() == 0 ? Eigen::VectorXd::Ones(n) : weights;
  SmoothingSpline s;
  s.x_ = x;
  s.second_ = Eigen::VectorXd::Zero(n);
  if (p == 0.0 || n == 2) {
    // Weighted least-squares line (for n = 2 it interpolates: every p agrees).
    const double sw = w.sum();
    const double mx = w.dot(x) / sw, my = w.dot(y) / sw;
    const Eigen::VectorXd dx = x.array() - mx;
    const double slope =
        w.dot((dx.array() * (y.array() - my)).matrix()) / w.dot((dx.array() * dx.array()).matrix());
    s.values_ = (my + slope * dx.array()).matrix();
    return s;
  }
  const double lambda = (1.0 - p) / p;
  const Eigen::Index m = n - 2;  // interior sites
  const Eigen::VectorXd h = x.tail(n - 1) - x.head(n - 1);
  // Q (n x m): column j (interior site j+1) holds 1/h_j, -1/h_j - 1/h_j+1, 1/h_j+1.
  auto q = [&](Eigen::Index row, Eigen::Index col) -> double {
    if (row == col) return 1.0 / h[col];
    if (row == col + 1) return -1.0 / h[col] - 1.0 / h[col + 1];
    if (row == col + 2) return 1.0 / h[col + 1];
    return 0.0;
  };
  // M = R + lambda Q^T W^-1 Q, pentadiagonal: entries (j, j+d), d = 0..2.
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(5 * m));
  for (Eigen::Index j = 0; j < m; ++j) {
    for (Eigen::Index d = 0; d <= 2 && j + d < m; ++d) {
      const Eigen::Index k = j + d;
      double v = 0.0;
      if (d == 0) v += (h[j] + h[j + 1]) / 3.0;
      if (d == 1) v += h[j + 1] / 6.0;
      // (Q^T W^-1 Q)_jk = sum over rows r shared by columns j and k.
      for (Eigen::Index r = k; r <= j + 2; ++r) v += lambda * q(r, j) * q(r, k) / w[r];
      t.emplace_back(j, k, v);
      if (d > 0) t.emplace_back(k, j, v);
    }
  }
  Eigen::SparseMatrix<double> M(m, m);
  M.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd qty(m);
  for (Eigen::Index j = 0; j < m; ++j)
    qty[j] = q(j, j) * y[j] + q(j + 1, j) * y[j + 1] + q(j + 2, j) * y[j + 2];
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(M);
  if (solver.info() != Eigen::Success) fail("the Reinsch system could not be factorised");
  const Eigen::VectorXd gamma = solver.solve(qty);
  // g = y - lambda W^-1 Q gamma.
  s.values_ = y;
  for (Eigen::Index j = 0; j < m; ++j) {
    for (Eigen::Index r = j; r <= j + 2; ++r) s.values_[r] -= lambda * q(r, j) * gamma[j] / w[r];
  }
  s.second_.segment(1, m) = gamma;
  return s;
}

double SmoothingSpline::evaluate(double x, int order) const {
  const Eigen::Index n = x_.size();
  if (order < 0 || order > 2) fail("derivative order must be 0, 1 or 2");
  // Outside: the natural spline continues as its end tangent line.
  if (x < x_[0] || x > x_[n - 1]) {
    const bool left = x < x_[0];
    const double x0 = left ? x_[0] : x_[n - 1];
    const double slope = evaluate(x0, 1);
    if (order == 2) return 0.0;
    if (order == 1) return slope;
    return evaluate(x0, 0) + slope * (x - x0);
  }
  const auto it = std::upper_bound(x_.data(), x_.data() + n, x);
  const Eigen::Index i = std::clamp<Eigen::Index>(it - x_.data() - 1, 0, n - 2);
  const double h = x_[i + 1] - x_[i];
  const double a = (x_[i + 1] - x) / h, b = 1.0 - a;
  const double gi = values_[i], gj = values_[i + 1], si = second_[i], sj = second_[i + 1];
  switch (order) {
    case 0:
      return a * gi + b * gj + ((a * a * a - a) * si + (b * b * b - b) * sj) * h * h / 6.0;
    case 1:
      return (gj - gi) / h - (3 * a * a - 1) / 6.0 * h * si + (3 * b * b - 1) / 6.0 * h * sj;
    default:
      return a * si + b * sj;
  }
}

}  // namespace cnclab
