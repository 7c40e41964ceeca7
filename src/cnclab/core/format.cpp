#include "cnclab/core/format.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace cnclab {

std::string shortest_double(double x) {
  char buf[32];
  // Whole numbers below 1e15 keep all their digits ("2000", not "2e+03").
  const double magnitude = std::fabs(x);
  const int integer_digits =
      magnitude >= 1 && magnitude < 1e15 ? static_cast<int>(std::log10(magnitude)) + 1 : 1;
  for (int precision = integer_digits; precision < 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, x);
    if (std::strtod(buf, nullptr) == x) return buf;
  }
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

std::string fixed_decimals(double x, int decimals) {
  char buf[384];  // %f of the largest double needs 309 digits before the point
  std::snprintf(buf, sizeof buf, "%.*f", decimals, x);
  return buf;
}

std::string join(const std::vector<std::string>& items, std::string_view sep) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (i > 0) out += sep;
    out += items[i];
  }
  return out;
}

}  // namespace cnclab
