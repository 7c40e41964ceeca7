#include "cnclab/deploy/predict_command.hpp"

#include <algorithm>
#include <cmath>

#include "cnclab/core/format.hpp"
#include "cnclab/deploy/prediction_file.hpp"
#include "cnclab/deploy/prediction_input.hpp"

namespace cnclab {
namespace {

const NamedColumn* find(const Prediction& p, const std::string& name) {
  for (const auto& c : p.columns) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

// "T.label: RMS r, max m unit" for every predicted column with a measured
// one (over the rows from first_step: the earlier ones repeat the
// measurement); of a model with physical columns, those only.
std::vector<std::string> differences(const DeployedModel& m, const Prediction& p) {
  std::vector<std::string> lines;
  for (const auto& c : p.columns) {
    const auto dot = c.name.rfind('.');
    if (dot == std::string::npos || c.name.substr(dot + 1) == "measured") continue;
    const std::string column = c.name.substr(0, dot);
    if (m.has_physical_columns() &&
        std::find(m.target_names.begin(), m.target_names.end(), column) != m.target_names.end()) {
      continue;
    }
    const NamedColumn* measured = find(p, column + ".measured");
    if (measured == nullptr) continue;
    const auto first = static_cast<Eigen::Index>(p.first_step);
    const Eigen::Index n = c.values.size() - first;
    if (n <= 0) continue;
    const Eigen::VectorXd d = c.values.tail(n) - measured->values.tail(n);
    lines.push_back("  " + c.name + " - measured: RMS " +
                    shortest_double(std::sqrt(d.squaredNorm() / static_cast<double>(n))) +
                    ", max " + shortest_double(d.cwiseAbs().maxCoeff()) + " " + c.unit);
  }
  return lines;
}

}  // namespace

std::vector<std::string> run_predict(const PredictRequest& r) {
  check_prediction_path(r.out);
  const DeployedModel model = load_deployed_model(r.result, r.data);
  const PredictionInput input =
      read_prediction_input(r.input, {r.overrides, r.data.data_dir, r.data.log});
  const Prediction p = predict(model, input, r.options);
  write_prediction(r.out, model, input, r.options, p);
  std::vector<std::string> lines = {
      "wrote " + r.out.string() + ": " + std::to_string(p.samples) + " samples of " + input.source +
      " (" + to_string(input.kind) + ", hash " + input.hash + ") through " + model.experiment +
      " (" + model.architecture() + ", result identity " + model.identity + ")"};
  for (const auto& n : p.notes) lines.push_back("  " + n);
  const auto diffs = differences(model, p);
  lines.insert(lines.end(), diffs.begin(), diffs.end());
  return lines;
}

}  // namespace cnclab
