#include "cnclab/experiment/spec_text.hpp"

#include <algorithm>

#include "cnclab/core/suggest.hpp"

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
    r.fail(key, one_of(allowed) + did_you_mean(value, allowed));
  }
  return value;
}

}  // namespace cnclab
