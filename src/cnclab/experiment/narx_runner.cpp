#include "cnclab/experiment/narx_runner.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <ostream>
#include <sstream>
#include <variant>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/progress.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/narx_stage_cache.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/run_warnings.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/train/narx_training.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// e_x -> x: the part after the last '_' (the whole name without one).
std::string axis_of(const std::string& target) {
  const auto cut = target.rfind('_');
  return cut == std::string::npos ? target : target.substr(cut + 1);
}

// The dataset rows of the targets (dataset.targets, default all).
std::vector<Eigen::Index> target_rows(const Dataset& d, const std::vector<std::string>& wanted) {
  std::vector<Eigen::Index> rows;
  for (std::size_t k = 0; k < d.target_names.size(); ++k) {
    const bool take = wanted.empty() ||
                      std::find(wanted.begin(), wanted.end(), d.target_names[k]) != wanted.end();
    if (take) rows.push_back(static_cast<Eigen::Index>(k));
  }
  return rows;
}

// The input rows of the network of target row k: input k (seed 002, model
// inputs empty), or <name>_<axis> for each name of model.inputs.
std::vector<Eigen::Index> network_input_rows(const Dataset& d, Eigen::Index k,
                                             const std::vector<std::string>& names) {
  if (names.empty()) {
    if (d.inputs.rows() != d.targets.rows()) {
      throw ConfigError("model.type narx: dataset " + d.generator + " has " +
                        std::to_string(d.inputs.rows()) + " inputs and " +
                        std::to_string(d.targets.rows()) +
                        " targets; one input per target, or model.inputs naming each network's "
                        "channels");
    }
    return {k};
  }
  const std::string axis = axis_of(d.target_names[static_cast<std::size_t>(k)]);
  std::vector<Eigen::Index> rows;
  for (const auto& name : names) {
    const std::string column = name + "_" + axis;
    const auto it = std::find(d.input_names.begin(), d.input_names.end(), column);
    if (it == d.input_names.end()) {
      throw ConfigError("model.inputs: the dataset (" + d.generator + ") has no input " + column +
                        " for target " + d.target_names[static_cast<std::size_t>(k)] +
                        "; its inputs: " + join(d.input_names, ", "));
    }
    rows.push_back(static_cast<Eigen::Index>(it - d.input_names.begin()));
  }
  return rows;
}

// Where a new independent sequence starts in [begin, end) (metadata
// `sequence`: an id per sample; absent: one sequence), relative to begin.
std::vector<Eigen::Index> sequence_starts(const Dataset& d, Eigen::Index begin, Eigen::Index end) {
  std::vector<Eigen::Index> starts;
  const Eigen::Index row = d.metadata_row("sequence");
  if (row < 0) return starts;
  for (Eigen::Index t = begin + 1; t < end; ++t) {
    if (d.metadata(row, t) != d.metadata(row, t - 1)) starts.push_back(t - begin);
  }
  return starts;
}

// One stage from `params` in place: series-parallel or parallel residuals
// over the training series, trained by the stage's trainer.
// One stage of one network, with its progress (epochs, SSE, mu) on `progress`.
Summary train_stage(const Narx& narx, const TrainingStage& stage, const Eigen::MatrixXd& v,
                    const Eigen::VectorXd& e, const std::vector<Eigen::Index>& starts,
                    Eigen::VectorXd& params, Progress& progress) {
  LmHooks hooks;
  hooks.on_epoch = [&](const EpochRecord& r, const LmEpochRecord& lm, const Eigen::VectorXd&) {
    std::ostringstream status;
    status << "SSE " << lm.sse << "  mu " << lm.mu;
    progress.update(r.epoch, status.str());
    return true;
  };
  const auto train = [&](ResidualObjective& objective) {
    return stage.trainer.def->train_residual(stage.trainer.options, objective, params, hooks);
  };
  if (stage.mode == StageMode::open_loop) {
    NarxOpenLoopObjective open(narx, v, e, starts);
    return train(open);
  }
  NarxClosedLoopObjective closed(narx, v, e, static_cast<Eigen::Index>(stage.horizon), starts);
  return train(closed);
}

// The final whole-series SSE of a recorded stage (its starting SSE when it
// took no step; infinity when it has neither).
double final_sse(const Summary& s) {
  if (!s.lm_history.empty()) return s.lm_history.back().sse;
  return s.lm_initial ? s.lm_initial->sse : INFINITY;
}

// fallback_horizon (narx_spec.hpp): the stage stopped on mu_max or diverged
// (params: where it stopped). Trains again from `start`, on windows of
// fallback_horizon steps for the first half of the stage's epochs, then on
// the whole series for the rest (the schedule measured in
// docs/narx_training.md), both recorded as second tries, and keeps the
// weights with the lower whole-series SSE. Returns the termination of the
// weights kept.
template <class RunStage>
Termination retry_stage(const TrainingStage& stage, const Eigen::VectorXd& start,
                        RunStage& run_stage, const NarxNetworkRecord& net, Eigen::VectorXd& params,
                        Termination first) {
  const Eigen::VectorXd first_params = params;
  const double first_sse =
      first == Termination::diverged ? INFINITY : final_sse(net.stages.back().summary);
  params = start;
  const std::size_t epochs = trainer_epochs(stage.trainer);
  const auto with_epochs = [](TrainingStage s, std::size_t n) {
    s.trainer.options = s.trainer.def->with_epochs(s.trainer.options, n);
    return s;
  };
  TrainingStage windowed = with_epochs(stage, (epochs + 1) / 2);
  windowed.horizon = stage.fallback_horizon;
  windowed.fallback_horizon = 0;
  run_stage(windowed, true);
  TrainingStage whole = with_epochs(stage, std::max<std::size_t>(epochs / 2, 1));
  whole.fallback_horizon = 0;
  const Termination second = run_stage(whole, true);
  if (second != Termination::diverged && final_sse(net.stages.back().summary) < first_sse) {
    return second;
  }
  params = first_params;
  return first;
}

const NarxNetworkRecord* upstream_network(const std::optional<UpstreamResult>& up,
                                          const std::string& axis) {
  if (!up) return nullptr;
  for (const auto& net : up->record.narx->networks) {
    if (net.axis == axis) return &net;
  }
  throw ConfigError("init_from: " + up->result_file.string() + " has no network for axis " + axis);
}

// init_from of a narx experiment: a complete narx result with the same network.
std::optional<UpstreamResult> upstream_results(const ExperimentSpec& spec, const RunOptions& o,
                                               RunRecord& rec) {
  std::optional<UpstreamResult> init;
  for (const auto& file : upstream_files(spec)) {
    UpstreamResult up = load_upstream(file, o.results_dir, spec.profile);
    rec.upstream.push_back({file.string(), up.result_file.string(), result_identity(up.record)});
    if (spec.init_from && file == spec.init_from->resolved_file) init = std::move(up);
  }
  if (!init) return init;
  const auto& r = init->record;
  if (r.provenance.status != "complete") {
    throw Error("init_from: " + init->result_file.string() + " is a failed run (" +
                r.provenance.failure_reason + "); nothing to start from");
  }
  const NarxOptions ours = spec.narx->options();
  if (!r.narx || r.narx->options.hidden != ours.hidden ||
      r.narx->options.hidden_activation != ours.hidden_activation ||
      r.narx->options.inputs != ours.inputs || r.narx->options.input_delays != ours.input_delays ||
      r.narx->options.feedback_delays != ours.feedback_delays) {
    throw ConfigError("init_from: " + init->result_file.string() +
                      " holds no narx network of this model's hidden size, activation, input "
                      "channels and delays");
  }
  return init;
}

}  // namespace

RunOutcome run_narx_experiment(const LoadedExperiment& experiment, const RunOptions& options) {
  const ExperimentSpec& spec = experiment.spec;
  const auto wall_start = std::chrono::steady_clock::now();
  RunRecord rec = start_run_record(experiment);
  const std::optional<UpstreamResult> init = upstream_results(spec, options, rec);

  const CachedDataset cached =
      obtain_run_dataset(spec, rec.provenance.derived_seeds["generator"], options);
  const Dataset& d = cached.dataset;
  rec.dataset_file = cached.path.string();
  rec.dataset_hash = cached.content_hash;
  const std::vector<Eigen::Index> rows = target_rows(d, spec.dataset.targets);
  Rng split_rng(spec.seed, "split");  // not drawn from: the halves are fixed
  rec.split = make_split(d.num_samples(), spec.split, split_rng);
  const auto n = static_cast<Eigen::Index>(d.num_samples());
  const auto half = static_cast<Eigen::Index>(rec.split.train.size());
  const std::vector<Eigen::Index> train_starts = sequence_starts(d, 0, half);
  const std::vector<Eigen::Index> val_starts = sequence_starts(d, half, n);

  NarxRecord narx_rec;
  narx_rec.options = spec.narx->options();
  const Narx narx(narx_rec.options);
  narx_rec.first_step = static_cast<std::size_t>(narx.first_step());
  narx_rec.predictions.resize(static_cast<Eigen::Index>(rows.size()), n - half);
  narx_rec.targets.resize(static_cast<Eigen::Index>(rows.size()), n - half);
  rec.trainer = stages_text(spec.stages);
  const NarxStageCache stage_cache(options.datasets_dir / "narx-stages");
  std::string message;
  bool ok = true;
  for (std::size_t a = 0; a < rows.size(); ++a) {
    const Eigen::Index k = rows[a];
    NarxNetworkRecord net;
    net.target = d.target_names[static_cast<std::size_t>(k)];
    net.axis = axis_of(net.target);
    const std::vector<Eigen::Index> in_rows = network_input_rows(d, k, spec.narx->inputs);
    Eigen::MatrixXd v(n, static_cast<Eigen::Index>(in_rows.size()));  // one column per channel
    for (std::size_t c = 0; c < in_rows.size(); ++c) {
      const auto row = static_cast<std::size_t>(in_rows[c]);
      net.inputs.push_back(d.input_names[row]);
      rec.input_names.push_back(d.input_names[row]);
      rec.input_units.push_back(d.input_units[row]);
      v.col(static_cast<Eigen::Index>(c)) = d.inputs.row(in_rows[c]).transpose();
    }
    rec.target_names.push_back(net.target);
    rec.target_units.push_back(d.target_units[static_cast<std::size_t>(k)]);
    const Eigen::VectorXd e = d.targets.row(k).transpose();
    const Eigen::MatrixXd v_train = v.topRows(half), v_val = v.bottomRows(n - half);
    const Eigen::VectorXd e_train = e.head(half), e_val = e.tail(n - half);
    Eigen::VectorXd params(static_cast<Eigen::Index>(narx.num_parameters()));
    const std::string stream = "narx/init/" + net.axis;
    rec.provenance.derived_seeds[stream] = derive_seed(spec.seed, stream);
    if (const NarxNetworkRecord* from = upstream_network(init, net.axis)) {
      params = from->parameters;
    } else {
      Rng rng(spec.seed, stream);
      narx.initialise(params, rng);
    }
    const auto t0 = std::chrono::steady_clock::now();
    message += (message.empty() ? "" : "; ") + net.axis + ":";
    // One stage from `params`, recorded; its termination.
    // A stage another run trained on the same series from the same weights
    // is read from the stage cache instead (narx_stage_cache.hpp).
    const auto run_stage = [&](const TrainingStage& stage, bool fallback) {
      const std::string label = to_string(stage.mode) + (fallback ? " (second try)" : "");
      const std::string key =
          stage_cache.key(narx.options(), stage, v_train, e_train, train_starts, params);
      Summary s;
      std::optional<CachedNarxStage> cached = stage_cache.find(key);
      if (cached && cached->params.size() == params.size()) {
        s = std::move(cached->summary);
        params = std::move(cached->params);
        if (options.log) {
          *options.log << "  " << spec.name << " " << net.axis << " " << label
                       << ": trained before, read from " << (stage_cache.dir() / key).string()
                       << ".h5\n";
        }
      } else {
        Progress progress(spec.name + " " + net.axis + " " + label, trainer_epochs(stage.trainer),
                          options.log ? *options.log : std::cerr,
                          {options.log ? options.progress : ProgressMode::quiet, 10.0, 0.1});
        s = train_stage(narx, stage, v_train, e_train, train_starts, params, progress);
        progress.finish(to_string(s.termination));
        stage_cache.store(key, {s, params});
      }
      message += " " + label + " " + std::to_string(s.history.size()) + " epochs (" +
                 to_string(s.termination) + ")";
      const Termination t = s.termination;
      net.stages.push_back({to_string(stage.mode), trainer_name(stage.trainer), std::move(s),
                            stage.horizon, fallback, stage.fallback_horizon});
      return t;
    };
    for (const auto& stage : spec.stages) {
      const Eigen::VectorXd start = params;
      Termination t = run_stage(stage, false);
      if (stage.fallback_horizon != 0 && (t == Termination::mu_max || t == Termination::diverged)) {
        t = retry_stage(stage, start, run_stage, net, params, t);
      }
      ok = ok && t != Termination::diverged;
      rec.training.termination = t;
    }
    net.seconds = seconds_since(t0);
    // Closed loop over the whole validation part (each sequence of it) from
    // measured initial states; those states stand in the predictions.
    const Eigen::Index first = narx.first_step();
    auto pred = narx_rec.predictions.row(static_cast<Eigen::Index>(a));
    for (const SequenceRange& q : sequence_ranges(n - half, val_starts, first)) {
      const Eigen::Index len = q.end - q.begin;
      const Eigen::VectorXd e_seq = e_val.segment(q.begin, len);
      pred.segment(q.begin, first) = e_seq.head(first).transpose();
      pred.segment(q.begin + first, len - first) =
          narx.simulate_closed_loop(params, v_val.middleRows(q.begin, len), e_seq).transpose();
    }
    narx_rec.targets.row(static_cast<Eigen::Index>(a)) = e_val.transpose();
    net.parameters = std::move(params);
    if (options.log) {
      *options.log << "  " << spec.name << " " << net.axis << ": " << rec.trainer << ", "
                   << net.stages.size() << " stage(s) in " << net.seconds << " s\n";
    }
    narx_rec.networks.push_back(std::move(net));
  }
  rec.training.message = message;

  if (ok) {
    SequencePrediction p;
    p.data = &d;
    p.first_validation = static_cast<std::size_t>(half);
    p.first_step = narx.first_step();
    p.sequence_starts = val_starts;
    for (std::size_t a = 0; a < rows.size(); ++a) {
      p.axes.push_back(narx_rec.networks[a].axis);
      p.target_rows.push_back(rows[a]);
      p.predicted.push_back(narx_rec.predictions.row(static_cast<Eigen::Index>(a)).transpose());
    }
    // The registered metrics are of the validation half: stored as
    // validation.<name> (spec.hpp, metric_splits_of).
    std::vector<std::string> wanted;
    for (const auto& name : stored_metrics(spec)) wanted.push_back(metric_base(name));
    for (const auto& [name, value] : sequence_metrics(p, wanted)) {
      rec.metrics[metric_name("validation", name)] = value;
    }
  }
  rec.narx = std::move(narx_rec);
  finish_provenance(rec.provenance);
  rec.provenance.wall_seconds = seconds_since(wall_start);
  rec.provenance.status = ok ? "complete" : "failed";
  if (ok) rec.warnings = prediction_warnings(rec);
  rec.provenance.failure_reason = ok ? "" : message;

  RunOutcome outcome;
  outcome.result_file = options.result_file.empty() ? result_path(experiment, options.results_dir)
                                                    : options.result_file;
  write_result(outcome.result_file, rec);
  outcome.ok = ok;
  outcome.message = message;
  outcome.metrics = rec.metrics;
  outcome.warnings = rec.warnings;
  outcome.notes = validation_notes(rec);
  return outcome;
}

}  // namespace cnclab
