#pragma once
// Results an experiment depends on (`needs:`, `init_from:`): where they are,
// what identifies their content, and the network check for init_from.
#include <filesystem>
#include <string>

#include "cnclab/experiment/run_record.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {

// The content of a result that downstream experiments consume, as 16 hex
// digits: FNV-1a over its config hash, status, network parameters and
// normaliser. Re-running an unchanged deterministic experiment gives the same
// identity, so its downstream results stay current.
std::string result_identity(const RunRecord& record);

struct UpstreamResult {
  LoadedExperiment experiment;
  std::filesystem::path result_file;
  RunRecord record;
};

// The result `cnclab run experiment_file` writes into `results_dir`
// (ResultStore::get, failed runs included). Throws MissingResults naming the
// experiment, the expected file and how to make it when there is none.
// `profile` is the downstream run's (ExperimentSpec::profile).
UpstreamResult load_upstream(const std::filesystem::path& experiment_file,
                             const std::filesystem::path& results_dir,
                             const std::string& profile = {});

// init_from needs the same network shape: layer sizes and activations (dropout
// may differ: it has no parameters). ConfigError naming both shapes otherwise.
void check_same_network(const MlpOptions& upstream, const MlpOptions& ours,
                        const std::filesystem::path& upstream_result);

// init_from.normaliser keep reuses the upstream's ScalingRecords: they must
// be of the methods (and min-max ranges) this experiment's `normalisation`
// names. ConfigError naming both otherwise.
void check_same_scaling(const RunRecord& upstream, const NormalisationSpec& ours,
                        const std::filesystem::path& upstream_result);

}  // namespace cnclab
