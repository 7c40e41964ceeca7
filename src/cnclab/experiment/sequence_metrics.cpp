#include "cnclab/experiment/sequence_metrics.hpp"

#include <algorithm>
#include <stdexcept>

#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace {

std::vector<SequenceMetricGroup>& sequence_metric_groups() {
  static std::vector<SequenceMetricGroup> groups;
  return groups;
}

}  // namespace

void register_sequence_metrics(SequenceMetricGroup group) {
  const auto known = sequence_metric_names();
  for (const auto& name : group.metrics) {
    if (std::find(known.begin(), known.end(), name) != known.end()) {
      throw std::logic_error("sequence metric '" + name + "' registered twice");
    }
  }
  sequence_metric_groups().push_back(std::move(group));
}

std::vector<std::string> sequence_metric_names() {
  std::vector<std::string> names;
  for (const auto& g : sequence_metric_groups())
    names.insert(names.end(), g.metrics.begin(), g.metrics.end());
  return names;
}

std::string sequence_metric_unit(const std::string& name) {
  for (const auto& g : sequence_metric_groups()) {
    if (const auto it = g.units.find(name); it != g.units.end()) return it->second;
  }
  return "";
}

MetricRange sequence_metric_range(const std::string& name) {
  for (const auto& g : sequence_metric_groups()) {
    if (const auto it = g.ranges.find(metric_base(name)); it != g.ranges.end()) return it->second;
  }
  return {};
}

std::map<std::string, double> sequence_metrics(const SequencePrediction& prediction,
                                               const std::vector<std::string>& wanted) {
  std::map<std::string, double> out;
  for (const auto& g : sequence_metric_groups()) {
    const bool used = std::any_of(g.metrics.begin(), g.metrics.end(), [&](const std::string& m) {
      return std::find(wanted.begin(), wanted.end(), m) != wanted.end();
    });
    if (!used) continue;
    const auto values = g.compute(prediction);
    for (const auto& name : wanted) {
      if (const auto it = values.find(name); it != values.end()) out[name] = it->second;
    }
  }
  return out;
}

}  // namespace cnclab
