#pragma once
// Metrics of a sequence model's trial (model.type narx): computed from the
// closed-loop prediction of the validation part and the whole dataset
// (metadata included), so a study can score what its data means (seed 002:
// following errors in µm, the contour error predicted from them). The
// experiment module knows no such metric itself: a study registers a group
// (src/cli/builtins.cpp -> register_<paper>_study()), and `metrics:` of a
// narx experiment accepts the registered names (default: all of them).
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cnclab/data/dataset.hpp"
#include "cnclab/nn/metric_range.hpp"

namespace cnclab {

struct SequencePrediction {
  const Dataset* data = nullptr;     // the whole dataset, metadata included
  std::size_t first_validation = 0;  // first sample of the validation part
  // Steps of the validation part that are initial states: predicted[a][t]
  // for t < first_step is the measured value, not a prediction.
  Eigen::Index first_step = 0;
  // Where a further independent sequence starts in the validation part
  // (metadata `sequence`; empty: one): its first first_step values are
  // measured initial states as well.
  std::vector<Eigen::Index> sequence_starts;
  std::vector<std::string> axes;          // per network: its axis name (e_x -> x)
  std::vector<Eigen::Index> target_rows;  // per network: its row of data->targets
  // Per network, the validation part in the dataset's (target) units.
  std::vector<Eigen::VectorXd> predicted;
};

struct SequenceMetricGroup {
  std::string owner;                 // who registered it, for messages
  std::vector<std::string> metrics;  // the names it computes
  // Every name of `metrics` (NaN where it does not apply).
  std::function<std::map<std::string, double>(const SequencePrediction&)> compute;
  std::map<std::string, std::string> units;   // per metric ("µm", "1"); absent: unknown
  std::map<std::string, MetricRange> ranges;  // per metric (a distance: >= 0); absent: unbounded
};

// std::logic_error when a name is registered twice.
void register_sequence_metrics(SequenceMetricGroup group);
// Every registered name, in registration order.
std::vector<std::string> sequence_metric_names();
// The unit a group registered for `name`; "" when none did.
std::string sequence_metric_unit(const std::string& name);
// The range a group registered for `name` (or its base, "contour_rms" of
// "validation.contour_rms"); unbounded when none did.
MetricRange sequence_metric_range(const std::string& name);
// The metrics `wanted` (registered names) of one prediction.
std::map<std::string, double> sequence_metrics(const SequencePrediction& prediction,
                                               const std::vector<std::string>& wanted);

}  // namespace cnclab
