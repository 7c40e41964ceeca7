#pragma once
// A trained network as `cnclab predict` and `cnclab export` use it: what the
// result file says about who it is (identity, metrics), its network(s) and
// every scaling between the columns a user gives and the network's own units.
//
// mlp (seed 000's step error, seed 004's IK networks): the dataset's columns
// are physical; the result's normalisation (input_scaling, target_scaling,
// nn/scaling.hpp) maps them to the network's units and back.
// narx (seed 002): one network per target, in the dataset's units. Where the
// dataset's generator scales its columns itself (seed 002's following_error:
// mapminmax of each physical column over the whole run), a registered
// SequenceExtension (sequence_extension.hpp) names the physical column
// behind each network input and target and its range: `physical_inputs`,
// `physical_targets` below (empty: the dataset's units are the only ones).
#include <Eigen/Core>
#include <cstdint>
#include <filesystem>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "cnclab/data/split.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/nn/narx.hpp"
#include "cnclab/nn/scaling.hpp"

namespace cnclab {

struct RunRecord;
struct SequenceExtension;

// A physical column behind a dataset column that its generator scaled with
// mapminmax to [-1, 1] (data/following_error.hpp, normalise_minmax and
// to_physical; the same arithmetic, so a column maps to the stored bits):
//   dataset = (x - min) / (max - min) * 2 - 1,
//   x       = min + (dataset + 1) * 0.5 * (max - min).
struct ColumnScaling {
  std::string name;             // the physical column, a metadata column of the dataset ("v_ref_x")
  std::string unit;             // its unit ("mm/s")
  double min = 0.0, max = 1.0;  // its range over the training dataset, min < max

  double to_dataset(double x) const { return (x - min) / (max - min) * 2.0 - 1.0; }
  double to_physical(double y) const { return min + (y + 1.0) * 0.5 * (max - min); }
};

// One SISO network of a narx result: target `target` from input `input`.
struct NarxNetwork {
  std::string axis;            // e_x -> x
  std::string input, target;   // the dataset's column names
  Eigen::VectorXd parameters;  // Narx layout (nn/narx.hpp)
};

enum class ModelKind { mlp, narx };
std::string to_string(ModelKind kind);

struct DeployedModel {
  ModelKind kind = ModelKind::mlp;
  // Where it came from: the result file as given, the experiment's name,
  // result_identity() (experiment/upstream.hpp) and the config hash.
  std::string result_file, experiment, identity, config_hash;
  std::string trained_utc;  // the run's end time
  std::string cnclab_version, git_commit;
  std::string generator;                  // the training dataset's generator (its registered name)
  std::string dataset_file;               // the training dataset's file when it ran (a cache file)
  std::string dataset_hash;               // the training dataset's content hash
  std::uint64_t generator_seed = 0;       // its generator seed (provenance "generator")
  std::string resolved_yaml;              // the result's resolved config (its dataset section)
  std::map<std::string, double> metrics;  // every metric of the result, whatever its name
  std::map<std::string, std::string> metric_units;
  // The dataset's columns the model reads and predicts (per narx network:
  // inputs[a] -> targets[a]).
  std::vector<std::string> input_names, input_units, target_names, target_units;
  Split split;  // the result's split of its training dataset (narx: the halves)

  // mlp
  MlpOptions mlp;
  Eigen::VectorXd parameters;
  ScalingRecord input_scaling, target_scaling;

  // narx
  NarxOptions narx;
  std::vector<NarxNetwork> networks;
  std::vector<ColumnScaling> physical_inputs, physical_targets;  // per network, or empty
  const SequenceExtension* extension = nullptr;  // registered for `generator`, or null

  std::size_t num_inputs() const { return input_names.size(); }
  std::size_t num_outputs() const { return target_names.size(); }
  bool has_physical_columns() const { return !physical_inputs.empty(); }
  std::size_t num_parameters() const;
  // The columns an export reads and writes (and the units): the physical
  // ones where the model has them, else the dataset's.
  std::vector<std::string> export_input_names() const;
  std::vector<std::string> export_input_units() const;
  std::vector<std::string> export_output_names() const;
  std::vector<std::string> export_output_units() const;
  // "mlp 73-28-20-1 (relu hidden, linear output)", "narx, 2 network(s) of 12
  // tanh units, input delays 0..3, feedback delays 1..4"
  std::string architecture() const;
};

// The model of a training result (`record` read from `result_file`).
// ConfigError (exit 2: nothing to predict with) naming the file for a job
// result, a result whose training failed (with its reason), or parameters
// that do not fit the network or are not finite. Physical columns are not
// filled (they need the training dataset): load_deployed_model does.
DeployedModel deployed_model(const RunRecord& record, const std::string& result_file);

// Where the training dataset comes from when a model needs it (a narx
// model's physical ranges, `--split`, the float bound's statement): the
// result's own dataset file when it still holds the same content, else the
// dataset cache in `data_dir`, generated there when absent (progress on
// `log`).
struct TrainingDataOptions {
  std::filesystem::path data_dir = "datasets";  // the dataset cache (`--data-dir`)
  std::ostream* log = nullptr;                  // progress and notes; null: quiet
};

// Reads `result_file` (read_result) and makes its model; for a narx model
// whose generator has a registered SequenceExtension, obtains the training
// dataset and fills the physical columns from it.
DeployedModel load_deployed_model(const std::filesystem::path& result_file,
                                  const TrainingDataOptions& data);

}  // namespace cnclab
