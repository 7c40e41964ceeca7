#include "cnclab/geometry/bspline_basis.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

constexpr double kExactTol = 1e-14;
constexpr double kFiniteDifferenceTol = 1e-6;

// The NURBS Book Ex. 2.3: U = {0,0,0,1,2,3,4,4,5,5,5}, p = 2, u = 5/2 lies in
// span 4 with N_2,2 = 1/8, N_3,2 = 6/8, N_4,2 = 1/8.
const std::vector<double> kBookKnots = {0, 0, 0, 1, 2, 3, 4, 4, 5, 5, 5};

TEST(BsplineBasis, BookExample2_3) {
  EXPECT_EQ(find_span(kBookKnots, 2, 2.5), 4);
  BasisDerivatives n;
  basis_derivatives(kBookKnots, 2, 4, 2.5, 2, n);
  EXPECT_NEAR(n[0][0], 1.0 / 8, kExactTol);
  EXPECT_NEAR(n[0][1], 6.0 / 8, kExactTol);
  EXPECT_NEAR(n[0][2], 1.0 / 8, kExactTol);
  // Ex. 2.4 (first derivatives at 5/2): N'_2,2 = -1/2, N'_3,2 = 0, N'_4,2 = 1/2.
  EXPECT_NEAR(n[1][0], -0.5, kExactTol);
  EXPECT_NEAR(n[1][1], 0.0, kExactTol);
  EXPECT_NEAR(n[1][2], 0.5, kExactTol);
  // Second derivatives of quadratic pieces on unit knot intervals: 1, -2, 1.
  EXPECT_NEAR(n[2][0], 1.0, kExactTol);
  EXPECT_NEAR(n[2][1], -2.0, kExactTol);
  EXPECT_NEAR(n[2][2], 1.0, kExactTol);
}

TEST(BsplineBasis, FindSpanAtKnotsAndEnds) {
  EXPECT_EQ(find_span(kBookKnots, 2, 0.0), 2);
  EXPECT_EQ(find_span(kBookKnots, 2, 1.0), 3);
  EXPECT_EQ(find_span(kBookKnots, 2, 4.0), 7);  // double knot 4: last span starting at 4
  EXPECT_EQ(find_span(kBookKnots, 2, 5.0), 7);  // the end belongs to the last span
  EXPECT_EQ(find_span(kBookKnots, 2, 7.0), 7);
  EXPECT_EQ(find_span(kBookKnots, 2, -1.0), 2);
}

// Partition of unity and derivative sums 0; derivatives against central
// differences of the values, for degrees 1..6 on random knot vectors.
TEST(BsplineBasis, PartitionOfUnityAndFiniteDifferences) {
  Rng rng(7);
  for (int p = 1; p <= 6; ++p) {
    std::vector<double> knots(static_cast<std::size_t>(p + 1), 0.0);
    double t = 0.0;
    for (int i = 0; i < 5; ++i) knots.push_back(t += rng.uniform(0.2, 1.0));
    knots.push_back(t += rng.uniform(0.2, 1.0));
    for (int i = 0; i < p; ++i) knots.push_back(t);
    validate_knot_vector(knots, p, knots.size() - static_cast<std::size_t>(p) - 1, "test");
    for (int trial = 0; trial < 50; ++trial) {
      const double u = rng.uniform(knots.front() + 1e-3, knots.back() - 1e-3);
      const int span = find_span(knots, p, u);
      if (std::abs(u - knots[span]) < 1e-4 || std::abs(u - knots[span + 1]) < 1e-4) continue;
      BasisDerivatives n, plus, minus;
      basis_derivatives(knots, p, span, u, 2, n);
      double sum[3] = {0, 0, 0};
      for (int j = 0; j <= p; ++j) {
        for (int k = 0; k < 3; ++k) sum[k] += n[k][j];
      }
      EXPECT_NEAR(sum[0], 1.0, kExactTol);
      EXPECT_NEAR(sum[1], 0.0, 1e-10);
      EXPECT_NEAR(sum[2], 0.0, 1e-8);
      const double h = 1e-6;
      basis_derivatives(knots, p, span, u + h, 2, plus);
      basis_derivatives(knots, p, span, u - h, 2, minus);
      for (int j = 0; j <= p; ++j) {
        EXPECT_NEAR(n[1][j], (plus[0][j] - minus[0][j]) / (2 * h), kFiniteDifferenceTol) << p;
        EXPECT_NEAR(n[2][j], (plus[1][j] - minus[1][j]) / (2 * h), 1e-4 * (1 + std::abs(n[2][j])))
            << p;
      }
    }
  }
}

std::string option_error(const std::vector<double>& knots, int degree, std::size_t points) {
  return testing::error_message<OptionError>(
      [&] { validate_knot_vector(knots, degree, points, "surface u"); });
}

TEST(BsplineBasis, KnotVectorValidationNamesTheRule) {
  EXPECT_NE(option_error({0, 0, 1, 1}, 0, 2).find("degree = 0: must be in [1, 15]"),
            std::string::npos);
  EXPECT_NE(option_error({0, 0, 0, 1, 1, 1}, 2, 2).find("needs at least 3 control points"),
            std::string::npos);
  EXPECT_NE(option_error({0, 0, 0, 1, 1}, 2, 3).find("must have (control points + degree + 1) = 6"),
            std::string::npos);
  EXPECT_NE(option_error({0, 0, 0, 0.7, 0.5, 1, 1, 1}, 2, 5).find("must be non-decreasing"),
            std::string::npos);
  EXPECT_NE(option_error({0, 0, 0.1, 0.5, 1, 1, 1}, 2, 4).find("clamped"), std::string::npos);
  EXPECT_NE(option_error({0, 0, 0, 0.5, 0.5, 0.5, 1, 1, 1}, 2, 6).find("at most degree = 2 times"),
            std::string::npos);
  EXPECT_NE(option_error({1, 1, 1, 1, 1, 1}, 2, 3).find("non-empty"), std::string::npos);
  EXPECT_NE(option_error({0, 0, NAN, 1, 1, 1}, 2, 3).find("finite"), std::string::npos);
  EXPECT_EQ(option_error({0, 0, 0, 0.5, 0.5, 1, 1, 1}, 2, 5), "no error");
}

}  // namespace
}  // namespace cnclab
