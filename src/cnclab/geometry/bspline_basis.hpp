#pragma once
// B-spline basis functions on clamped knot vectors (The NURBS Book, Piegl &
// Tiller, 2nd ed.): knot span search (A2.1) and basis functions with their
// derivatives (A2.3).
#include <array>
#include <span>
#include <string>
#include <vector>

namespace cnclab {

// Highest supported degree: the basis workspace lives on the stack (no heap
// allocation per evaluation). Free-form CAD surfaces rarely exceed degree 9.
inline constexpr int kMaxBsplineDegree = 15;
// Highest derivative order the evaluators return (point, first, second).
inline constexpr int kMaxDerivativeOrder = 2;

// Throws OptionError(`name`, ...) unless: 1 <= degree <= kMaxBsplineDegree,
// num_points >= degree + 1, knots.size() == num_points + degree + 1, every
// knot finite, the vector non-decreasing, clamped (first and last degree + 1
// knots equal), no interior knot repeated more than `degree` times, and the
// parameter range non-empty.
void validate_knot_vector(const std::vector<double>& knots, int degree, std::size_t num_points,
                          const std::string& name);

// A2.1: the span index s with knots[s] <= t < knots[s+1], degree <= s <= n,
// where n = knots.size() - degree - 2; t = knots[n+1] (the end) maps to n.
// t outside [knots[degree], knots[n+1]] is clamped to the range.
int find_span(std::span<const double> knots, int degree, double t);

// Basis values and derivatives at t in span `span`:
// ders[k][j] = d^k N_{span-degree+j, degree}(t) / dt^k, k <= order, j <= degree.
using BasisDerivatives =
    std::array<std::array<double, kMaxBsplineDegree + 1>, kMaxDerivativeOrder + 1>;

// A2.3 (DersBasisFuns), order <= kMaxDerivativeOrder (higher orders of a
// degree-p basis, k > p, are zero and returned as such).
void basis_derivatives(std::span<const double> knots, int degree, int span, double t, int order,
                       BasisDerivatives& ders);

}  // namespace cnclab
