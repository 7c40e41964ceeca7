#include "cnclab/experiment/result_inference.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace {

constexpr const char* kGroup = "/other_inference";

DropoutInference parse_inference(const H5File& f, const std::string& object,
                                 const std::string& attr) {
  const std::string text = f.attribute_string(object, attr);
  if (text == "deterministic") return DropoutInference::deterministic;
  if (text == "mc") return DropoutInference::mc;
  throw IoError(f.path().string() + ": " + object + ": unknown " + attr + " '" + text + "'");
}

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

void write_inference(H5File& f, const RunRecord& r) {
  f.set_attribute("/model", "dropout_inference", to_string(r.model.dropout_inference));
  f.set_attribute("/model", "dropout_mc_samples",
                  static_cast<std::int64_t>(r.model.dropout_mc_samples));
  if (!r.other_inference) return;
  const OtherInference& o = *r.other_inference;
  f.create_group(kGroup);
  f.set_attribute(kGroup, "inference", to_string(o.inference));
  f.set_attribute(kGroup, "mc_samples", static_cast<std::int64_t>(r.model.dropout_mc_samples));
  for (const auto& [name, value] : o.metrics) f.set_attribute(kGroup, name, value);
  f.write_matrix(std::string(kGroup) + "/test_predictions", o.test_predictions,
                 join(r.target_units, ","));
}

void read_inference(const H5File& f, RunRecord& r) {
  if (f.has_attribute("/model", "dropout_inference")) {
    r.model.dropout_inference = parse_inference(f, "/model", "dropout_inference");
    r.model.dropout_mc_samples =
        static_cast<std::size_t>(f.attribute_int("/model", "dropout_mc_samples"));
  }
  if (!f.is_group(kGroup)) return;
  OtherInference o;
  o.inference = parse_inference(f, kGroup, "inference");
  for (const auto& name : f.attribute_names(kGroup)) {
    if (name != "inference" && name != "mc_samples") {
      o.metrics[name] = f.attribute_double(kGroup, name);
    }
  }
  o.test_predictions = f.read_matrix(std::string(kGroup) + "/test_predictions");
  r.other_inference = std::move(o);
}

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
