#pragma once
// Everything one run produced, in memory: what result_file.cpp writes and
// reads back. Plain data.
#include <Eigen/Core>
#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/data/split.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/nn/narx.hpp"
#include "cnclab/nn/scaling.hpp"
#include "cnclab/train/summary.hpp"

namespace cnclab {

// An upstream result this run depended on (needs / init_from) when it ran.
struct UpstreamRef {
  std::string experiment;   // the upstream experiment file, as resolved
  std::string result_file;  // its result file
  std::string identity;     // result_identity() of that result (upstream.hpp)
};

// A file a job wrote beside its result (job_result.hpp).
struct OutputRef {
  std::string role;  // "program", "points", "report", ...
  std::string file;  // relative to the result file's folder
};

// A network with dropout evaluated the other way than its
// model.dropout.inference (deterministic <-> mc, nn/mlp.hpp), so that one
// training answers both (seed 000 Table 2 under both evaluations).
struct OtherInference {
  DropoutInference inference = DropoutInference::mc;
  Eigen::MatrixXd test_predictions;       // physical units, as RunRecord's
  std::map<std::string, double> metrics;  // the run's metrics, evaluated this way
};

// One trained network of a narx run (model.type narx): one target.
struct NarxStageRecord {
  std::string mode;     // open_loop | closed_loop
  std::string trainer;  // the stage's trainer.type
  Summary summary;
  std::size_t horizon = 0;           // closed_loop window length (0: the whole series)
  bool fallback = false;             // a second try of the stage before it (fallback_horizon)
  std::size_t fallback_horizon = 0;  // as configured (second tries only when it stopped)
};
struct NarxNetworkRecord {
  std::string axis;  // e_x -> x
  // The dataset's column names: the input channels in network order
  // (seed 002: one, the axis velocity) and the target.
  std::vector<std::string> inputs;
  std::string target;
  Eigen::VectorXd parameters;  // Narx layout (nn/narx.hpp)
  std::vector<NarxStageRecord> stages;
  double seconds = 0;  // training time of this network
};
struct NarxRecord {
  NarxOptions options;
  std::vector<NarxNetworkRecord> networks;  // in target order
  // Closed-loop prediction of the validation part per network (rows), in the
  // dataset's target units; the first `first_step` columns are the measured
  // initial states. `targets`: the measured values.
  Eigen::MatrixXd predictions, targets;
  std::size_t first_step = 0;
};

struct RunRecord {
  // "train": a training run (everything below). Any other value: the result
  // of a `kind: <job>` file (job_result.hpp), which has only the experiment
  // name, config, provenance, metrics, upstream, outputs and facts.
  std::string kind = "train";
  // The result format the file was written in (kResultFormatVersion,
  // result_file.hpp; a record made in memory: the current one). Files of an
  // older format are read, their metrics under today's names.
  int format_version = 2;
  std::string experiment;     // spec.name
  std::string resolved_yaml;  // the full resolved config
  std::string config_hash;    // identity of the run: hash of resolved_yaml
  Provenance provenance;
  std::string dataset_file;  // path of the cached dataset used
  std::string dataset_hash;  // its content hash
  std::vector<std::string> input_names, input_units, target_names, target_units;

  Split split;
  MlpOptions model;  // inputs/outputs filled in
  Eigen::VectorXd parameters;
  ScalingRecord input_scaling, target_scaling;

  std::string trainer;  // trainer.type (trainer_spec.hpp; train/trainer_registry.hpp)
  Summary training;
  std::vector<double> test_loss;  // per epoch, MSE in normalised units (NaN if no test set)

  // Under model.dropout.inference: physical units, one sample per column.
  Eigen::MatrixXd test_predictions;
  Eigen::MatrixXd test_targets;
  std::map<std::string, double> metrics;
  // The other evaluation of a network with dropout (/other_inference);
  // absent without dropout (both ways are the same network) and in results
  // written before it was stored.
  std::optional<OtherInference> other_inference;
  // Each metric's unit ("µm²", "1"; "" unknown), stored apart from the values
  // (/metrics/units). Training records: training_metric_units (result_file.hpp)
  // when written; jobs: what the job sets.
  std::map<std::string, std::string> metric_units;
  // Complete results that are not useful ones ("constant predictions";
  // run_warnings.hpp); root attribute `warnings`.
  std::vector<std::string> warnings;
  std::vector<UpstreamRef> upstream;  // empty without needs / init_from

  // Job results only.
  std::vector<OutputRef> outputs;
  std::map<std::string, std::string> facts;  // named text a job reports (selected trial, ...)

  // model.type narx: the networks (model, parameters, training and test_*
  // above are then unused).
  std::optional<NarxRecord> narx;
};

}  // namespace cnclab
