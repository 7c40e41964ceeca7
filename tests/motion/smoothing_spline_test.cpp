#include "cnclab/motion/smoothing_spline.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"

namespace cnclab {
namespace {

struct Data {
  Eigen::VectorXd x, y;
};

// Non-uniform sites, noisy smooth data.
Data sample_data(int n, std::uint64_t seed) {
  Rng rng(seed);
  Data d{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  double x = 0.0;
  for (int i = 0; i < n; ++i) {
    x += rng.uniform(0.5, 1.5);
    d.x[i] = x;
    d.y[i] = std::sin(0.4 * x) + 0.1 * rng.normal();
  }
  return d;
}

// The natural cubic interpolant built independently: 4 coefficients per
// piece from the interpolation, C1, C2 and natural end conditions, solved
// densely.
Eigen::VectorXd natural_interpolant_coefficients(const Data& d) {
  const int n = static_cast<int>(d.x.size()), pieces = n - 1;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(4 * pieces, 4 * pieces);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(4 * pieces);
  int row = 0;
  for (int i = 0; i < pieces; ++i) {
    const double h = d.x[i + 1] - d.x[i];
    A(row, 4 * i) = 1;  // f_i(0) = y_i
    b[row++] = d.y[i];
    A.block(row, 4 * i, 1, 4) << 1, h, h * h, h * h * h;  // f_i(h) = y_i+1
    b[row++] = d.y[i + 1];
    if (i + 1 < pieces) {
      A.block(row, 4 * i, 1, 4) << 0, 1, 2 * h, 3 * h * h;  // f_i'(h) = f_i+1'(0)
      A(row++, 4 * (i + 1) + 1) = -1;
      A.block(row, 4 * i, 1, 4) << 0, 0, 2, 6 * h;  // f_i''(h) = f_i+1''(0)
      A(row++, 4 * (i + 1) + 2) = -2;
    }
  }
  A(row++, 2) = 2;  // f_0''(0) = 0
  const double h_last = d.x[n - 1] - d.x[n - 2];
  A.block(row++, 4 * (pieces - 1), 1, 4) << 0, 0, 2, 6 * h_last;
  return A.fullPivLu().solve(b);
}

TEST(SmoothingSpline, PEqualOneIsTheNaturalCubicInterpolant) {
  const Data d = sample_data(12, 3);
  const Eigen::VectorXd c = natural_interpolant_coefficients(d);
  for (const double p : {1.0, 1.0 - 1e-12}) {
    const SmoothingSpline s = SmoothingSpline::fit(d.x, d.y, p);
    for (int i = 0; i + 1 < d.x.size(); ++i) {
      for (const double f : {0.0, 0.3, 0.77}) {
        const double t = f * (d.x[i + 1] - d.x[i]);
        const double expected =
            c[4 * i] + t * (c[4 * i + 1] + t * (c[4 * i + 2] + t * c[4 * i + 3]));
        EXPECT_NEAR(s(d.x[i] + t), expected, 1e-9) << "p " << p << " piece " << i;
      }
    }
  }
}

TEST(SmoothingSpline, PToZeroIsTheLeastSquaresLine) {
  const Data d = sample_data(40, 5);
  // Normal equations of y = a + b x.
  Eigen::MatrixXd X(d.x.size(), 2);
  X.col(0).setOnes();
  X.col(1) = d.x;
  const Eigen::Vector2d ab = (X.transpose() * X).ldlt().solve(X.transpose() * d.y);
  for (const double p : {0.0, 1e-12}) {
    const SmoothingSpline s = SmoothingSpline::fit(d.x, d.y, p);
    for (int i = 0; i < d.x.size(); ++i) {
      EXPECT_NEAR(s.values()[i], ab[0] + ab[1] * d.x[i], 1e-6) << "p " << p << " site " << i;
    }
  }
}

TEST(SmoothingSpline, InteriorActsAsTheClosedFormFilter) {
  // Uniform unit spacing (the sample index): a sinusoid comes out scaled by
  // H(w) = 1 / (1 + lambda 48 sin^4(w/2) / (2 + cos w)), lambda = (1-p)/p,
  // the symbol of (I + lambda Q R^-1 Q^T)^-1 on an infinite uniform grid.
  const int n = 2001;
  const double p = 5e-2, lambda = (1 - p) / p;
  for (const double w : {0.1, 0.48, 1.2}) {
    Eigen::VectorXd x(n), y(n);
    for (int k = 0; k < n; ++k) {
      x[k] = k;
      y[k] = std::sin(w * k + 0.3);
    }
    const SmoothingSpline s = SmoothingSpline::fit(x, y, p);
    const double sw = std::sin(w / 2);
    const double H = 1.0 / (1.0 + lambda * 48 * sw * sw * sw * sw / (2 + std::cos(w)));
    for (int k = 900; k <= 1100; ++k) {
      EXPECT_NEAR(s.values()[k], H * y[k], 1e-9) << "w " << w << " k " << k;
    }
    if (w == 0.48) {
      EXPECT_NEAR(H, 0.5, 0.05);  // the half-power point quoted in the header
    }
  }
}

TEST(SmoothingSpline, RejectsBadInput) {
  Eigen::VectorXd x(3), y(3);
  x << 0, 1, 1;
  y << 0, 1, 2;
  EXPECT_THROW(SmoothingSpline::fit(x, y, 0.5), Error);  // not increasing
  x << 0, 1, 2;
  EXPECT_THROW(SmoothingSpline::fit(x, y, 1.5), Error);
  y[1] = std::nan("");
  try {
    SmoothingSpline::fit(x, y, 0.5);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("y[1] = nan"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cnclab
