#pragma once
// An experiment: what `cnclab run` reads from YAML. Every section maps onto a
// typed options struct of the module that uses it; reading is strict (see
// core/config.hpp) and validate() of each struct runs with the YAML location.
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/core/config.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/core/override.hpp"
#include "cnclab/data/dataset_spec.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/data/split.hpp"
#include "cnclab/experiment/narx_spec.hpp"
#include "cnclab/experiment/trainer_spec.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/nn/scaling.hpp"

namespace cnclab {

// normalisation: {inputs: zscore|minmax|none, targets: ..., input_range:
// [low, high], target_range: [low, high]}, fitted on the training split
// only: zscore = seed 000 Eq. 7 (n-1 sample std), minmax = MATLAB mapminmax
// to the range (default [-1, 1], seed 002 and Bayesian regularisation's usual companion; a
// sigmoid output needs one inside (0, 1), seed 004). See scaling.hpp.
struct NormalisationSpec {
  Scaling inputs = Scaling::zscore;
  Scaling targets = Scaling::zscore;
  std::array<double, 2> input_range = {-1.0, 1.0};   // minmax only: [low, high], low < high
  std::array<double, 2> target_range = {-1.0, 1.0};  // minmax only
};

// init_from: {experiment: FILE, normaliser: refit|keep}: start training from
// the network parameters another experiment's result holds (fine-tuning,
// transfer learning). The upstream result is the one `cnclab run FILE` writes
// into the same results folder; its network must have the same layer sizes
// and activations. `normaliser` says where the input and target scaling come
// from (seed 000 does not say which its transfer stages use):
//   refit  fitted on this experiment's training split (`normalisation`), the
//          default;
//   keep   the upstream result's stored ScalingRecords, unchanged (the network
//          sees new data through the old normaliser). Needs the same scaling
//          methods in `normalisation`, and is the only choice with no
//          training samples (split train 0, trainer.epochs 0).
enum class NormaliserSource { refit, keep };
std::string to_string(NormaliserSource s);

struct InitFromSpec {
  std::string experiment;               // as written: path relative to this file
  std::filesystem::path resolved_file;  // the upstream experiment file
  NormaliserSource normaliser = NormaliserSource::refit;
};

struct ExperimentSpec {
  std::string name;
  std::string description;
  std::uint64_t seed = 0;  // master seed: every random stream derives from it by name
  DatasetSpec dataset;
  SplitOptions split;
  NormalisationSpec normalisation;
  // model: type mlp; `inputs`/`outputs` come from the dataset at run time.
  MlpOptions model;
  TrainerSpec trainer;  // trainer: {type: a registered trainer, ...} (trainer_spec.hpp)
  // model.type narx (narx_spec.hpp): one NARX network per target, trained in
  // `stages` (trainer.stages); `model` and `trainer` are then unused. A narx
  // experiment needs split.mode sequential_halves and normalisation none (the
  // following_error generator scales its columns itself).
  std::optional<NarxModelSpec> narx;
  std::vector<TrainingStage> stages;
  // metrics: names of nn/metrics.hpp (mlp) or registered sequence metrics
  // (narx): a base name is that metric on every split the run has
  // (stored_metrics), "<split>.<base>" that one only.
  std::vector<std::string> metrics = {"mse", "rmse", "mae", "max_abs_error", "r2"};
  // needs: [FILE, ...]: experiments whose results this one depends on (paths
  // relative to the experiment file given, also when the key comes from an
  // include). `cnclab reproduce` runs them first and re-runs
  // this one when their results change. init_from's experiment is implied.
  std::vector<std::string> needs;
  std::vector<std::filesystem::path> needs_files;  // resolved paths of `needs`
  std::optional<InitFromSpec> init_from;
  // may_diverge: true says a diverged training is this experiment's expected
  // outcome, not a failure: a sweep point whose settings are known to be
  // unstable (seed 000 Table 2 with the paper's settings) still is a result,
  // shown as "diverged" in its table. `run` and `reproduce` then exit 0; the
  // result keeps status "failed" with the reason. Default false: a diverged
  // run is a failure (exit 1).
  bool may_diverge = false;

  std::filesystem::path source_file;
  // The `profiles:` entry applied when loading ("" = none; core/config.hpp).
  // Upstream experiments (needs, init_from) load with the same profile.
  std::string profile;
  // The `key=value` overrides applied when loading, as given, then
  // `seed=N` for a seed override (recorded in the result's provenance).
  std::vector<std::string> overrides;
  // What the reader changed on its own (LoadedExperiment::notes); not configuration.
  std::vector<std::string> reader_notes;
};

// Every key of a `kind: train` file, declared once (core/fields.hpp): the
// reader, the resolved config (so the result identity), `cnclab schema` and
// the key tables loop over it. Rules across sections (the split against the
// sample count, dropout with LM, metric names, upstream files) are checked
// by the reader after it.
const FieldList<ExperimentSpec>& experiment_fields();

// The splits an experiment's metrics are computed on, of metric_splits()
// (nn/metrics.hpp), leaving out a part the split gives no samples (no
// validation split: no validation.*). mlp: train, validation, test. narx
// (split.mode sequential_halves): validation only; the second half is held
// out of training (no stage stops on it) and is what seed 002 reports; there
// is no test part, so a narx selection is chosen and reported on the same
// half.
std::vector<std::string> metric_splits_of(const ExperimentSpec& spec);
// What a result of `spec` stores: spec.metrics through expand_metric_selection
// over metric_splits_of(spec) ("rmse" -> train.rmse, validation.rmse,
// test.rmse). A split that turns out empty at run time stores none.
std::vector<std::string> stored_metrics(const ExperimentSpec& spec);

struct LoadedExperiment {
  ExperimentSpec spec;
  // The full resolved configuration, defaults included, as YAML: what
  // `validate` prints and every result file stores. Reloading it gives the
  // same spec.
  std::string resolved_yaml;
  // One line each for the user: what the reader changed on its own (keys of
  // another trainer dropped after a trainer.type switch).
  std::vector<std::string> notes;
};

// Loads, merges includes, applies the `profile` (profiles: block, see
// core/config.hpp), then `key=value` overrides (then --seed), reads and
// validates everything. Throws ConfigError naming file:line:col, key, value
// and rule; unknown keys are errors.
LoadedExperiment load_experiment(const std::filesystem::path& file,
                                 const std::vector<std::string>& overrides = {},
                                 std::optional<std::uint64_t> seed_override = std::nullopt,
                                 const std::string& profile = {});

// The same with already parsed overrides (sweep trials).
LoadedExperiment load_experiment(const std::filesystem::path& file,
                                 const std::vector<Override>& overrides,
                                 std::optional<std::uint64_t> seed_override,
                                 const std::string& profile = {});

// The upstream experiment files (needs and init_from), without duplicates.
std::vector<std::filesystem::path> upstream_files(const ExperimentSpec& spec);

// The same from YAML text (tests and fuzzing); `origin` names it in messages.
LoadedExperiment parse_experiment(const std::string& yaml_text, const std::string& origin,
                                  const std::vector<std::string>& overrides = {});

std::string to_yaml(const ExperimentSpec& spec);

// The generator seed of an experiment: dataset.seed, or the stream
// "generator" derived from the master seed.
std::uint64_t generator_seed(const ExperimentSpec& spec);

// The required `name` key of an experiment file: a file-name-safe identifier
// (letters, digits, '_', '-', '.'; no leading '.'), else ConfigError.
std::string read_experiment_name(const ConfigReader& root);

// An experiment file named at `key` (text as written), relative to the
// folder `base` of the file that names it; ConfigError naming the key unless
// it exists. Lexically normalised.
std::filesystem::path upstream_file(const ConfigReader& r, const std::string& key,
                                    const std::string& text, const std::filesystem::path& base);

}  // namespace cnclab
