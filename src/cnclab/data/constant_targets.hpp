#pragma once
// Targets that do not vary: a network trained on them learns nothing, and
// its metrics read as chance (a flat CAD face gives step errors of ~1e-11
// µm, rounding noise: training reports r2 = -0.05 and completes). Checked
// when a dataset is generated (a warning on the log) and when a run uses it
// (a warning on the result, run_warnings.hpp), the way degenerate
// predictions are (nn/constant_predictions.hpp).
//
// The rule, per target row r of n samples with population standard
// deviation s_r and magnitude m_r = max |y_r|:
//   near_constant(r)  <=>  n >= 2  and  ( s_r <= kConstantTargetRatio * m_r
//                                         or s_r <= resolution_r )
// The first clause: constant to six digits relative to the targets' own
// magnitude (all 5.0, or 5.0 plus noise); the second: a spread below the
// generator's declared resolution of that target
// (DatasetGenerator::target_resolution), which catches noise around zero
// that has no magnitude to be relative to. NaNs make no clause true.
#include <string>
#include <vector>

#include "cnclab/data/dataset.hpp"

namespace cnclab {

inline constexpr double kConstantTargetRatio = 1e-6;
inline constexpr const char* kConstantTargets = "constant targets";

struct ConstantTarget {
  std::string name, unit;
  double std = 0;         // s_r
  double magnitude = 0;   // m_r
  double resolution = 0;  // the generator's floor (0: none declared)
};

// The near-constant targets of `d` by the rule above, in row order;
// `resolution` per target row (DatasetGenerator::target_resolution; shorter
// or empty: none for the rest).
std::vector<ConstantTarget> constant_targets(const Dataset& d,
                                             const std::vector<double>& resolution);

// constant_targets of `all` (a generator's dataset, with its resolutions)
// that `selected` (select_targets of it: what a run learns) kept.
class DatasetGenerator;
std::vector<ConstantTarget> selected_constant_targets(const Dataset& all, const Dataset& selected,
                                                      const DatasetGenerator& generator);

// "constant targets (step_error)"; "" for none: the result's warning.
std::string constant_targets_warning(const std::vector<ConstantTarget>& targets);

// The log's sentence: "target step_error has no spread to learn: std 4.1e-12
// µm, below the generator's resolution 1e-06 µm (max |y| 2.5e-11 µm); a
// network trained on it learns nothing (r2 near or below 0)".
std::string constant_target_text(const ConstantTarget& target);

}  // namespace cnclab
