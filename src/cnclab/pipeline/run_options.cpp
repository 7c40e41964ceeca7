#include "cnclab/pipeline/run_options.hpp"

#include <vector>

#include "cnclab/nn/metrics.hpp"

namespace cnclab {

std::string metrics_line(const std::map<std::string, double>& metrics) {
  // Grouped by split, in metric_splits() order, then names without one:
  // "train: mse 0.1, rmse 0.3; validation: ...; test: ...".
  std::vector<std::string> groups = metric_splits();
  groups.emplace_back("");
  std::string s;
  for (const auto& split : groups) {
    std::string part;
    for (const auto& [k, v] : metrics) {
      if (metric_split(k) != split) continue;
      part += (part.empty() ? "" : ", ") + metric_base(k) + " " + format_metric(v);
    }
    if (!part.empty()) s += (s.empty() ? "" : "; ") + (split.empty() ? "" : split + ": ") + part;
  }
  return s;
}

RunOptions run_options(const CommandOptions& options, std::ostream& log) {
  RunOptions r;
  r.results_dir = options.results_dir;
  r.datasets_dir = options.datasets_dir;
  r.progress = options.quiet ? ProgressMode::quiet : ProgressMode::automatic;
  r.log = options.quiet ? nullptr : &log;
  r.regenerate_dataset = options.regenerate;
  return r;
}

}  // namespace cnclab
