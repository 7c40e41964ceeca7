#include "cnclab/experiment/upstream.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/experiment/result_store.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

std::span<const double> values(const Eigen::VectorXd& v) {
  return {v.data(), static_cast<std::size_t>(v.size())};
}

std::string network_text(const MlpOptions& m) {
  std::string s = std::to_string(m.inputs);
  for (auto h : m.hidden) s += "-" + std::to_string(h);
  s += "-" + std::to_string(m.outputs);
  return s + " (" + to_string(m.hidden_activation) + "/" + to_string(m.output_activation) + ")";
}

}  // namespace

std::string result_identity(const RunRecord& r) {
  Hasher h;
  h.add(r.config_hash).add(std::string_view("\n")).add(r.provenance.status);
  for (const Eigen::VectorXd* v : {&r.parameters, &r.input_scaling.mean, &r.input_scaling.std,
                                   &r.target_scaling.mean, &r.target_scaling.std}) {
    h.add(static_cast<std::uint64_t>(v->size())).add(values(*v));
  }
  if (r.narx) {
    for (const auto& net : r.narx->networks) {
      h.add(static_cast<std::uint64_t>(net.parameters.size())).add(values(net.parameters));
    }
  }
  return h.hex();
}

UpstreamResult load_upstream(const fs::path& experiment_file, const fs::path& results_dir,
                             const std::string& profile) {
  const ResultStore store(results_dir, profile);
  UpstreamResult up{store.load(experiment_file), {}, {}};
  // Failed upstream runs are returned: init_from refuses them (runner.cpp),
  // needs records them.
  try {
    StoredResult r = store.get(up.experiment, Accept::complete_or_failed);
    up.result_file = std::move(r.file);
    up.record = std::move(r.record);
  } catch (const MissingResults& e) {
    throw MissingResults("upstream experiment " + experiment_file.string() + " has no result: " +
                         e.what() + " (`cnclab reproduce` runs upstream experiments first)");
  }
  return up;
}

void check_same_network(const MlpOptions& upstream, const MlpOptions& ours,
                        const fs::path& upstream_result) {
  const bool same = upstream.inputs == ours.inputs && upstream.outputs == ours.outputs &&
                    upstream.hidden == ours.hidden &&
                    upstream.hidden_activation == ours.hidden_activation &&
                    upstream.output_activation == ours.output_activation;
  if (!same) {
    throw ConfigError("init_from: " + upstream_result.string() + " holds a network " +
                      network_text(upstream) + " but this experiment builds " + network_text(ours) +
                      "; model.hidden and the activations must match to start from its "
                      "parameters (and the dataset its inputs/outputs)");
  }
}

void check_same_scaling(const RunRecord& upstream, const NormalisationSpec& ours,
                        const fs::path& upstream_result) {
  const auto check = [&](const char* key, const ScalingRecord& theirs, Scaling method,
                         const std::array<double, 2>& range) {
    const bool same =
        theirs.method == method &&
        (method != Scaling::minmax || (theirs.y_min == range[0] && theirs.y_max == range[1]));
    if (!same) {
      throw ConfigError("init_from.normaliser keep: " + upstream_result.string() + " scaled its " +
                        key + " with " + to_string(theirs.method) + " but normalisation." + key +
                        " is " + to_string(method) +
                        "; give the same normalisation (or normaliser: refit)");
    }
  };
  check("inputs", upstream.input_scaling, ours.inputs, ours.input_range);
  check("targets", upstream.target_scaling, ours.targets, ours.target_range);
}

}  // namespace cnclab
