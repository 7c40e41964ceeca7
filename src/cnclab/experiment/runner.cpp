#include "cnclab/experiment/runner.hpp"

#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/core/resources.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/constant_targets.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/narx_runner.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/experiment/training.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// Named random streams of a run; the names are part of the reproducibility
// contract (stored in the result's provenance).
constexpr const char* kStreams[] = {"generator", "split",   "init",
                                    "dropout",   "shuffle", "mc_dropout"};

Eigen::MatrixXd columns(const Eigen::MatrixXd& m, const std::vector<std::size_t>& idx) {
  Eigen::MatrixXd out(m.rows(), static_cast<Eigen::Index>(idx.size()));
  for (std::size_t j = 0; j < idx.size(); ++j)
    out.col(static_cast<Eigen::Index>(j)) = m.col(static_cast<Eigen::Index>(idx[j]));
  return out;
}

// Estimate before allocating: the dataset is held about four times (as
// generated or read, split into parts, normalised parts, test predictions),
// the network's parameters four times (parameters, velocity, gradient, best),
// and one activation per unit and evaluated sample.
void check_run_memory(const ExperimentSpec& spec) {
  const auto [samples, inputs, all_outputs] = spec.dataset.generator->shape();
  const std::size_t outputs =
      spec.dataset.targets.empty() ? all_outputs : spec.dataset.targets.size();
  const double n = static_cast<double>(samples);
  const double values = static_cast<double>(inputs + outputs);
  double parameters = 0, units = static_cast<double>(inputs + outputs);
  std::size_t fan_in = inputs;
  for (std::size_t width : spec.model.hidden) {
    parameters += static_cast<double>((fan_in + 1) * width);
    units += static_cast<double>(width);
    fan_in = width;
  }
  parameters += static_cast<double>((fan_in + 1) * outputs);
  const double bytes = 8.0 * (4.0 * n * values + 4.0 * parameters + 2.0 * n * units) +
                       trainer_workspace_bytes(spec.trainer, parameters);
  check_memory(bytes, spec.name + ": the run (" + std::to_string(samples) + " samples x " +
                          std::to_string(inputs + outputs) + " values, " +
                          std::to_string(static_cast<std::uint64_t>(parameters)) +
                          " network parameters)");
}

}  // namespace

CachedDataset obtain_run_dataset(const ExperimentSpec& spec, std::uint64_t seed,
                                 const RunOptions& options) {
  StagedProgress generation("dataset " + spec.dataset.generator->name(),
                            options.log ? *options.log : std::cerr,
                            {options.log ? options.progress : ProgressMode::quiet, 5.0, 0.1});
  return obtain_dataset(spec.dataset, seed, options.datasets_dir, options.log,
                        options.regenerate_dataset, generation.callback());
}

RunRecord start_run_record(const LoadedExperiment& experiment) {
  RunRecord rec;
  rec.experiment = experiment.spec.name;
  rec.resolved_yaml = experiment.resolved_yaml;
  rec.config_hash = hash_hex(experiment.resolved_yaml);
  rec.provenance = make_provenance(experiment.spec.seed);
  rec.provenance.overrides = experiment.spec.overrides;
  rec.provenance.profile = experiment.spec.profile;
  set_project(rec.provenance, experiment.spec.source_file.parent_path());
  rec.provenance.derived_seeds["generator"] = generator_seed(experiment.spec);
  return rec;
}

RunOutcome run_experiment(const LoadedExperiment& experiment, const RunOptions& options) {
  if (experiment.spec.narx) return run_narx_experiment(experiment, options);
  const ExperimentSpec& spec = experiment.spec;
  const auto wall_start = std::chrono::steady_clock::now();
  RunRecord rec = start_run_record(experiment);
  for (const char* stream : kStreams)
    rec.provenance.derived_seeds[stream] = derive_seed(spec.seed, stream);

  check_run_memory(spec);

  // Upstream results (needs, init_from) first: a missing one stops the run
  // before any work.
  std::optional<UpstreamResult> init_source;
  for (const auto& file : upstream_files(spec)) {
    UpstreamResult up = load_upstream(file, options.results_dir, spec.profile);
    rec.upstream.push_back({file.string(), up.result_file.string(), result_identity(up.record)});
    if (spec.init_from && file == spec.init_from->resolved_file) init_source = std::move(up);
  }
  if (init_source && init_source->record.provenance.status != "complete") {
    throw Error("init_from: " + init_source->result_file.string() + " is a failed run (" +
                init_source->record.provenance.failure_reason + "); nothing to start from");
  }

  // Dataset (generated or reused from the cache).
  const CachedDataset cached =
      obtain_run_dataset(spec, rec.provenance.derived_seeds["generator"], options);
  const Dataset data = select_targets(cached.dataset, spec.dataset.targets);
  const std::string target_warning = constant_targets_warning(
      selected_constant_targets(cached.dataset, data, *spec.dataset.generator));
  rec.dataset_file = cached.path.string();
  rec.dataset_hash = cached.content_hash;
  rec.input_names = data.input_names;
  rec.input_units = data.input_units;
  rec.target_names = data.target_names;
  rec.target_units = data.target_units;

  // Split.
  Rng split_rng(spec.seed, "split");
  rec.split = make_split(data.num_samples(), spec.split, split_rng);
  // (load_experiment checked that the training part is large enough.)
  Eigen::MatrixXd x_train = columns(data.inputs, rec.split.train);
  Eigen::MatrixXd y_train = columns(data.targets, rec.split.train);
  Eigen::MatrixXd x_val = columns(data.inputs, rec.split.validation);
  Eigen::MatrixXd y_val = columns(data.targets, rec.split.validation);
  Eigen::MatrixXd x_test = columns(data.inputs, rec.split.test);
  Eigen::MatrixXd y_test = columns(data.targets, rec.split.test);

  // Normalisation: fitted on the training split only (scaling.hpp), or the
  // upstream network's own (init_from.normaliser keep).
  const NormalisationSpec& norm = spec.normalisation;
  if (init_source && spec.init_from->normaliser == NormaliserSource::keep) {
    check_same_scaling(init_source->record, norm, init_source->result_file);
    rec.input_scaling = init_source->record.input_scaling;
    rec.target_scaling = init_source->record.target_scaling;
  } else {
    rec.input_scaling = ScalingRecord::fit(norm.inputs, x_train, norm.input_range);
    rec.target_scaling = ScalingRecord::fit(norm.targets, y_train, norm.target_range);
  }
  const auto scale_x = [&](const Eigen::MatrixXd& m) { return rec.input_scaling.transform(m); };
  const auto scale_y = [&](const Eigen::MatrixXd& m) { return rec.target_scaling.transform(m); };
  const Eigen::MatrixXd xn_train = scale_x(x_train), yn_train = scale_y(y_train);
  const Eigen::MatrixXd xn_val = scale_x(x_val), yn_val = scale_y(y_val);
  const Eigen::MatrixXd xn_test = scale_x(x_test), yn_test = scale_y(y_test);

  // Model.
  rec.model = spec.model;
  rec.model.inputs = static_cast<std::size_t>(data.inputs.rows());
  rec.model.outputs = static_cast<std::size_t>(data.targets.rows());
  rec.model.validate();
  const Mlp mlp(rec.model);
  Rng init_rng(spec.seed, "init");
  Eigen::VectorXd params;
  if (init_source) {
    // Fine-tuning: start from the upstream network's trained parameters.
    check_same_network(init_source->record.model, rec.model, init_source->result_file);
    params = init_source->record.parameters;
  } else {
    mlp.initialise(params, init_rng);
  }

  // Training, with the test loss recorded after every epoch.
  const auto mse = [&](const Eigen::VectorXd& p, const Eigen::MatrixXd& x,
                       const Eigen::MatrixXd& y) {
    if (x.cols() == 0) return std::nan("");
    return (mlp.predict(p, x) - y).array().square().mean();
  };
  rec.trainer = trainer_name(spec.trainer);
  Progress progress("train " + spec.name, trainer_epochs(spec.trainer),
                    options.log ? *options.log : std::cerr,
                    {options.log ? options.progress : ProgressMode::quiet, 5.0, 0.1});
  TrainingHooks hooks;
  if (!rec.split.validation.empty()) {
    hooks.validation_loss = [&](const Eigen::VectorXd& p) { return mse(p, xn_val, yn_val); };
  }
  std::size_t pruned_at = 0;  // the epoch options.report stopped training at
  const auto report = [&](const EpochRecord& e, const Eigen::VectorXd& p) {
    if (!options.report || e.epoch % options.report_every != 0) return true;
    std::map<std::string, SplitData> split;
    if (!rec.split.validation.empty()) {
      SplitData& d = split["validation"];
      d.outputs = mlp.predict(p, xn_val);
      d.scaled_targets = yn_val;
      d.predictions = rec.target_scaling.inverse_transform(d.outputs);
      d.targets = y_val;
    }
    const auto m = evaluation_metrics(split, {options.report_metric});
    const auto it = m.find(options.report_metric);
    if (options.report(e.epoch, it == m.end() ? std::nan("") : it->second)) return true;
    pruned_at = e.epoch;
    return false;
  };
  hooks.on_epoch = [&](const EpochRecord& e, const Eigen::VectorXd& p) {
    rec.test_loss.push_back(mse(p, xn_test, yn_test));
    std::ostringstream status;
    status << "train loss " << e.train_loss << "  test loss " << rec.test_loss.back();
    progress.update(e.epoch, status.str());
    return report(e, p);
  };
  if (trainer_epochs(spec.trainer) == 0) {
    // trainer.epochs 0: evaluate the starting network as it is.
    rec.training.message = "trainer.epochs 0: evaluation only, no parameter update";
  } else {
    rec.training = train_network(spec.trainer, mlp, xn_train, yn_train, params, spec.seed, hooks);
  }
  progress.finish();
  rec.parameters = params;
  const bool ok = rec.training.termination != Termination::diverged;

  // Evaluation of every split in physical units and in the network's
  // normalised units (nn/metrics.hpp), under model.dropout.inference; a
  // network with dropout also the other way (RunRecord::other_inference): one
  // training, both answers, each with metrics named "<split>.<base>".
  if (ok) {
    const auto evaluate = [&](DropoutInference inference) {
      std::map<std::string, SplitData> splits;
      const auto add = [&](const char* split, const Eigen::MatrixXd& xn, const Eigen::MatrixXd& yn,
                           const Eigen::MatrixXd& y) {
        // Monte-Carlo masks: one stream per split under "mc_dropout", so a
        // split's masks depend on nothing else evaluated.
        Rng rng(rec.provenance.derived_seeds.at("mc_dropout"), split);
        SplitData& d = splits[split];
        d.outputs =
            xn.cols() > 0 ? mlp.infer(params, xn, inference, rng) : Eigen::MatrixXd(yn.rows(), 0);
        d.scaled_targets = yn;
        d.predictions = rec.target_scaling.inverse_transform(d.outputs);
        d.targets = y;
      };
      add("train", xn_train, yn_train, y_train);
      add("validation", xn_val, yn_val, y_val);
      add("test", xn_test, yn_test, y_test);
      return splits;
    };
    const std::vector<std::string> wanted = stored_metrics(spec);
    const auto splits = evaluate(rec.model.dropout_inference);
    rec.test_predictions = splits.at("test").predictions;
    rec.test_targets = y_test;
    rec.metrics = evaluation_metrics(splits, wanted);
    if (mlp.has_any_dropout()) {
      OtherInference other;
      other.inference = rec.model.dropout_inference == DropoutInference::mc
                            ? DropoutInference::deterministic
                            : DropoutInference::mc;
      const auto other_splits = evaluate(other.inference);
      other.test_predictions = other_splits.at("test").predictions;
      other.metrics = evaluation_metrics(other_splits, wanted);
      rec.other_inference = std::move(other);
    }
  }

  finish_provenance(rec.provenance);
  rec.provenance.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  rec.provenance.status = !ok ? "failed" : pruned_at > 0 ? "pruned" : "complete";
  if (ok) rec.warnings = prediction_warnings(rec);
  if (ok && !target_warning.empty()) rec.warnings.push_back(target_warning);
  rec.provenance.failure_reason =
      !ok             ? rec.training.message
      : pruned_at > 0 ? "pruned by the sweep's pruner after epoch " + std::to_string(pruned_at)
                      : "";

  RunOutcome outcome;
  outcome.result_file = options.result_file.empty() ? result_path(experiment, options.results_dir)
                                                    : options.result_file;
  write_result(outcome.result_file, rec);
  outcome.ok = ok;
  outcome.message = rec.training.message;
  outcome.metrics = rec.metrics;
  outcome.warnings = rec.warnings;
  outcome.notes = validation_notes(rec);
  return outcome;
}

}  // namespace cnclab
