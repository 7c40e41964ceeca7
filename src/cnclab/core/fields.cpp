#include "cnclab/core/fields.hpp"

#include <algorithm>
#include <regex>

namespace cnclab {
namespace {

std::string number(double v, bool integer) {
  return integer ? std::to_string(static_cast<long long>(v)) : shortest_double(v);
}

}  // namespace

bool Rule::holds(double v) const {
  if (finite && !std::isfinite(v)) return false;
  if (min && (min->inclusive ? v < min->value : v <= min->value)) return false;
  if (max && (max->inclusive ? v > max->value : v >= max->value)) return false;
  return true;
}

bool Rule::holds(const std::string& v) const {
  if (!pattern.empty() && !std::regex_match(v, std::regex(pattern))) return false;
  return choices.empty() || std::find(choices.begin(), choices.end(), v) != choices.end();
}

std::string Rule::text(bool integer) const {
  if (!pattern.empty()) return pattern_text;
  if (!choices.empty()) {
    std::string s = "must be one of: ";
    for (std::size_t i = 0; i < choices.size(); ++i) s += (i ? ", " : "") + choices[i];
    return s;
  }
  if (min && max) {
    return std::string("must be in ") + (min->inclusive ? "[" : "(") + number(min->value, integer) +
           ", " + number(max->value, integer) + (max->inclusive ? "]" : ")");
  }
  if (min && integer && min->inclusive) return "must be at least " + number(min->value, true);
  const std::string what = integer ? "must be an integer " : "must be a finite number ";
  if (min) return what + (min->inclusive ? ">= " : "> ") + number(min->value, integer);
  if (max) return what + (max->inclusive ? "<= " : "< ") + number(max->value, integer);
  if (finite) return integer ? "must be an integer" : "must be a finite number";
  return "";
}

}  // namespace cnclab
