#include "cnclab/experiment/result_inference.hpp"

#include "cnclab/core/format.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace {

// "deterministic" or "mc (100 masks)".
std::string inference_text(DropoutInference inference, std::size_t passes) {
  return inference == DropoutInference::mc ? "mc (mean of " + std::to_string(passes) + " masks)"
                                           : "deterministic";
}

// `own` when r was evaluated by `inference`, `other` when its other
// evaluation was; a network without dropout is the same either way (`own`);
// nullptr otherwise (written before the other evaluation was stored).
template <class T>
const T* by_inference(const RunRecord& r, DropoutInference inference, const T* own,
                      const T* other) {
  if (r.model.dropout_inference == inference) return own;
  if (r.other_inference && r.other_inference->inference == inference) return other;
  return Mlp(r.model).has_any_dropout() ? nullptr : own;
}

}  // namespace

void print_inference(const RunRecord& r, std::ostream& out) {
  if (!r.other_inference) return;
  const std::size_t n = r.model.dropout_mc_samples;
  out << "inference    dropout evaluated " << inference_text(r.model.dropout_inference, n)
      << " above; " << inference_text(r.other_inference->inference, n) << ":\n ";
  for (const auto& [name, value] : r.other_inference->metrics) {
    out << " " << name << " " << format_metric(value);
  }
  out << "\n";
}

const Eigen::MatrixXd* test_predictions_by(const RunRecord& r, DropoutInference inference) {
  return by_inference(r, inference, &r.test_predictions,
                      r.other_inference ? &r.other_inference->test_predictions : nullptr);
}

const std::map<std::string, double>* metrics_by(const RunRecord& r, DropoutInference inference) {
  return by_inference(r, inference, &r.metrics,
                      r.other_inference ? &r.other_inference->metrics : nullptr);
}

}  // namespace cnclab
