#include "cnclab/data/constant_targets.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cnclab/core/format.hpp"
#include "cnclab/data/generator.hpp"

namespace cnclab {

std::vector<ConstantTarget> constant_targets(const Dataset& d,
                                             const std::vector<double>& resolution) {
  std::vector<ConstantTarget> out;
  const Eigen::Index n = d.targets.cols();
  if (n < 2) return out;
  for (Eigen::Index r = 0; r < d.targets.rows(); ++r) {
    const auto row = d.targets.row(r).array();
    const double mean = row.mean();
    const double s = std::sqrt((row - mean).square().mean());
    const double m = row.abs().maxCoeff();
    const auto i = static_cast<std::size_t>(r);
    const double floor = i < resolution.size() ? resolution[i] : 0.0;
    if (s <= kConstantTargetRatio * m || s <= floor) {
      out.push_back(
          {i < d.target_names.size() ? d.target_names[i] : "target " + std::to_string(i + 1),
           i < d.target_units.size() ? d.target_units[i] : "", s, m, floor});
    }
  }
  return out;
}

std::vector<ConstantTarget> selected_constant_targets(const Dataset& all, const Dataset& selected,
                                                      const DatasetGenerator& generator) {
  std::vector<ConstantTarget> out;
  for (auto& t : constant_targets(all, generator.target_resolution())) {
    const auto& kept = selected.target_names;
    if (std::find(kept.begin(), kept.end(), t.name) != kept.end()) out.push_back(std::move(t));
  }
  return out;
}

std::string constant_targets_warning(const std::vector<ConstantTarget>& targets) {
  if (targets.empty()) return "";
  std::vector<std::string> names;
  for (const auto& t : targets) names.push_back(t.name);
  return std::string(kConstantTargets) + " (" + join(names, ", ") + ")";
}

namespace {

std::string three_digits(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

}  // namespace

std::string constant_target_text(const ConstantTarget& t) {
  const std::string unit = t.unit.empty() || t.unit == "1" ? "" : " " + t.unit;
  const std::string std_text = "std " + three_digits(t.std) + unit;
  const std::string max_text = "max |y| " + three_digits(t.magnitude) + unit;
  return "target " + t.name + " has no spread to learn: " +
         (t.std <= t.resolution ? std_text + ", below the generator's resolution " +
                                      shortest_double(t.resolution) + unit + " (" + max_text + ")"
                                : std_text + " against " + max_text + " (below " +
                                      shortest_double(kConstantTargetRatio) + " of it)") +
         "; a network trained on it learns nothing (r2 near or below 0)";
}

}  // namespace cnclab
