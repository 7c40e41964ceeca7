#include "cnclab/report/run_settings.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>

#include "cnclab/core/config.hpp"
#include "cnclab/report/text_table.hpp"

namespace cnclab {
namespace {

constexpr const char* kAbsent = "(absent)";

// The value at dotted `key` below `node` as text, or kAbsent. (Recursive:
// assigning to a YAML::Node would rewrite the node it refers to.)
std::string value_at(const YAML::Node& node, const std::string& key) {
  const std::size_t dot = key.find('.');
  const std::string part = key.substr(0, dot);
  if (!node.IsMap() || !node[part]) return kAbsent;
  const YAML::Node child = node[part];
  return dot == std::string::npos ? node_text(child) : value_at(child, key.substr(dot + 1));
}

double as_number(const std::string& text) {
  try {
    std::size_t used = 0;
    const double v = std::stod(text, &used);
    return used == text.size() ? v : NAN;
  } catch (const std::exception&) {
    return NAN;
  }
}

// The distinct values of one key over the runs, as one phrase.
std::string values_phrase(std::vector<std::string> values) {
  const bool numbers = std::all_of(values.begin(), values.end(),
                                   [](const std::string& v) { return !std::isnan(as_number(v)); });
  if (numbers) {
    std::sort(values.begin(), values.end(), [](const std::string& a, const std::string& b) {
      return as_number(a) < as_number(b);
    });
    if (values.size() > 3) {
      return values.front() + " to " + values.back() + " (" + std::to_string(values.size()) +
             " values)";
    }
  }
  std::string out;
  for (std::size_t i = 0; i < values.size(); ++i) {
    out += (i == 0 ? "" : i + 1 == values.size() ? " or " : ", ") + values[i];
  }
  return out;
}

}  // namespace

std::string run_settings(const std::vector<std::string>& resolved_yamls,
                         const std::vector<std::string>& keys) {
  std::vector<YAML::Node> trees;
  for (const auto& text : resolved_yamls) trees.push_back(YAML::Load(text));
  std::string out, group;
  for (const auto& key : keys) {
    std::vector<std::string> values;
    for (const auto& tree : trees) {
      const std::string v = value_at(tree, key);
      if (std::find(values.begin(), values.end(), v) == values.end()) values.push_back(v);
    }
    if (values.empty() || (values.size() == 1 && values.front() == kAbsent)) continue;
    const std::size_t dot = key.find('.');
    const std::string head = dot == std::string::npos ? "" : key.substr(0, dot);
    const std::string rest = dot == std::string::npos ? key : key.substr(dot + 1);
    if (head != group || out.empty()) {
      out += (out.empty() ? "" : "; ") + (head.empty() ? "" : head + ": ");
      group = head;
    } else {
      out += ", ";
    }
    out += rest + " " + values_phrase(values);
  }
  return out;
}

std::string ran_with(const std::string& profile, const std::vector<std::string>& resolved_yamls,
                     const std::vector<std::string>& keys) {
  return (profile.empty() ? std::string("ran with no profile") : "ran with profile " + profile) +
         " (per the result files' configs): " + run_settings(resolved_yamls, keys);
}

}  // namespace cnclab
