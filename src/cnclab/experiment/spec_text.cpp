#include "cnclab/experiment/spec_text.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace cnclab {

std::string one_of(const std::vector<std::string>& names) {
  std::string s = "must be one of: ";
  for (std::size_t i = 0; i < names.size(); ++i) s += (i ? ", " : "") + names[i];
  return s;
}

std::string choice(const ConfigReader& r, const std::string& key, const std::string& fallback,
                   const std::vector<std::string>& allowed) {
  const auto value = r.get<std::string>(key, fallback);
  if (std::find(allowed.begin(), allowed.end(), value) == allowed.end()) {
    r.fail(key, one_of(allowed));
  }
  return value;
}

std::string yaml_number(double x) {
  char buf[32];
  if (x == std::trunc(x) && std::abs(x) < 1e6) {  // 10, not 1e+01
    std::snprintf(buf, sizeof buf, "%.0f", x);
    return buf;
  }
  std::snprintf(buf, sizeof buf, "%.17g", x);
  for (int precision = 1; precision < 17; ++precision) {
    char shorter[32];
    std::snprintf(shorter, sizeof shorter, "%.*g", precision, x);
    if (std::strtod(shorter, nullptr) == x) return shorter;
  }
  return buf;
}

}  // namespace cnclab
