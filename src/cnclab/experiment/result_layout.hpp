#pragma once
// The HDF5 layout of a result file (README.md, "Where results go"), declared
// once: each function below walks one part of a RunRecord with an Io that
// either writes it (ResultLayoutWriter, result_writer.cpp) or reads it back
// (ResultLayoutReader, result_reader.cpp), in the same order and under the
// same names. R is `const RunRecord` when writing, `RunRecord` when reading;
// a part read first (a scaling's method, the trainer) decides what follows.
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/result_layout_io.hpp"
#include "cnclab/experiment/run_record.hpp"
#include "cnclab/io/provenance.hpp"
#include "cnclab/train/trainer_registry.hpp"

namespace cnclab::result_layout {

inline bool parse_activation_name(const std::string& text, Activation& a) {
  try {
    a = parse_activation(text);
    return true;
  } catch (const OptionError&) {
    return false;
  }
}
template <class E, E... values>
bool parse_one_of(const std::string& text, E& e) {
  return ((to_string(values) == text ? (e = values, true) : false) || ...);
}
inline constexpr auto parse_dropout_placement =
    parse_one_of<DropoutPlacement, DropoutPlacement::between_hidden,
                 DropoutPlacement::after_every_hidden>;
inline constexpr auto parse_dropout_inference =
    parse_one_of<DropoutInference, DropoutInference::deterministic, DropoutInference::mc>;

// /model/layer_sizes: inputs, hidden..., outputs.
struct LayerSizes {
  std::vector<double> encode(const MlpOptions& m) const {
    std::vector<double> sizes{static_cast<double>(m.inputs)};
    for (auto h : m.hidden) sizes.push_back(static_cast<double>(h));
    sizes.push_back(static_cast<double>(m.outputs));
    return sizes;
  }
  std::string decode(const std::vector<double>& sizes, MlpOptions& m) const {
    if (sizes.size() < 2) return "needs at least 2 entries";
    m.inputs = static_cast<std::size_t>(sizes.front());
    m.outputs = static_cast<std::size_t>(sizes.back());
    m.hidden.clear();
    for (std::size_t i = 1; i + 1 < sizes.size(); ++i) {
      m.hidden.push_back(static_cast<std::size_t>(sizes[i]));
    }
    return "";
  }
};

// Root attributes experiment, config_hash, status (for h5ls; read from
// /provenance), /config and /provenance, of every result (jobs too). The
// format, `kind` and `warnings` attributes: write_result_header.
template <class Io, class R>
void header(Io& io, R& r) {
  io.attr("/", "experiment", r.experiment);
  io.attr("/", "config_hash", r.config_hash);
  io.note("/", "status", r.provenance.status);
  io.text("/config", r.resolved_yaml);
  io.provenance("/provenance", r.provenance);
}

// /metrics: one number attribute per metric, nothing else; /metrics/units:
// one text attribute per metric (absent in older files).
template <class Io, class M, class U>
void metrics(Io& io, M& values, U& units) {
  io.group("/metrics");
  io.attribute_map("/metrics", values, {"units"});
  if (io.part("/metrics/units", true)) {
    io.group("/metrics/units");
    io.attribute_map("/metrics/units", units);
  }
}

// /upstream: three lists, one entry per upstream result; absent without.
template <class Io, class U>
void upstream(Io& io, U& refs) {
  if (!io.part("/upstream", !refs.empty())) return;
  auto c = io.columns("/upstream", refs);
  c.strings("experiments", &UpstreamRef::experiment);
  c.strings("result_files", &UpstreamRef::result_file);
  c.strings("identities", &UpstreamRef::identity);
}

// Per epoch: epoch, train_loss, validation_loss, wall_seconds (one dataset each).
template <class Io, class H>
void epochs(Io& io, const std::string& g, H& history, const std::string& loss_units) {
  auto c = io.columns(g, history);
  c.column("epoch", &EpochRecord::epoch, "1");
  c.column("train_loss", &EpochRecord::train_loss, loss_units);
  c.column("validation_loss", &EpochRecord::validation_loss, loss_units);
  c.column("wall_seconds", &EpochRecord::wall_seconds, "s");
}

template <class Io, class S>
void scaling(Io& io, const std::string& g, S& s, const std::string& units) {
  io.group(g);
  io.choice(g, "method", s.method, parse_scaling);
  if (s.method == Scaling::zscore) {
    io.vector(g + "/mean", s.mean, units);
    io.vector(g + "/std", s.std, units);
  } else if (s.method == Scaling::minmax) {
    // y = (y_max - y_min) (x - min) / (max - min) + y_min; constant features
    // (min = max): y = x. Results written before the range was configurable
    // have no y_min, y_max: [-1, 1].
    io.note(g, "formula", "mapminmax to [y_min, y_max]");
    io.optional_attr(g, "y_min", s.y_min);
    io.optional_attr(g, "y_max", s.y_max);
    io.vector(g + "/min", s.min, units);
    io.vector(g + "/max", s.max, units);
  }
}

// How a network with dropout was evaluated (older files: deterministic), and
// /other_inference: the other evaluation, when stored.
template <class Io, class R>
void inference(Io& io, R& r) {
  io.optional_choice("/model", "dropout_inference", r.model.dropout_inference,
                     parse_dropout_inference);
  io.optional_attr("/model", "dropout_mc_samples", r.model.dropout_mc_samples);
  const std::string g = "/other_inference";
  if (!io.optional_part(g, r.other_inference)) return;
  auto& o = *r.other_inference;
  io.group(g);
  io.choice(g, "inference", o.inference, parse_dropout_inference);
  io.note(g, "mc_samples", r.model.dropout_mc_samples);
  io.attribute_map(g, o.metrics, {"inference", "mc_samples"});
  io.matrix(g + "/test_predictions", o.test_predictions, join(r.target_units, ","));
}

template <class Io, class R>
void mlp(Io& io, R& r) {
  io.group("/model");
  io.note("/model", "type", "mlp");
  io.encoded_vector("/model/layer_sizes", r.model, LayerSizes{}, "1");
  io.choice("/model", "hidden_activation", r.model.hidden_activation, parse_activation_name);
  io.choice("/model", "output_activation", r.model.output_activation, parse_activation_name);
  io.attr("/model", "dropout_keep_probability", r.model.dropout_keep_probability);
  // Read back so that Mlp(r.model) has the run's dropout layers (MC dropout).
  io.optional_choice("/model", "dropout_placement", r.model.dropout_placement,
                     parse_dropout_placement);
  inference(io, r);
  io.note("/model", "parameter_layout", "per layer: W (n_out x n_in, column-major) then b (n_out)");
  io.vector("/model/parameters", r.parameters, "1");
  scaling(io, "/model/input_scaling", r.input_scaling, join(r.input_units, ","));
  scaling(io, "/model/target_scaling", r.target_scaling, join(r.target_units, ","));

  io.group("/training");
  io.attr("/training", "trainer", r.trainer);
  io.choice("/training", "termination", r.training.termination, parse_termination);
  io.attr("/training", "message", r.training.message);
  io.attr("/training", "best_epoch", r.training.best_epoch);
  epochs(io, "/history", r.training.history, "normalised MSE");
  io.vector("/history/test_loss", r.test_loss, "normalised MSE");
  const TrainerDef* trainer = trainers().find(r.trainer);
  io.require(trainer != nullptr, "/training: unknown trainer '" + r.trainer + "'");
  if (trainer && trainer->history != TrainerHistory::epochs) {
    io.attr("/training", "beta_guard_count", r.training.beta_guard_count);
    io.lm_history("/history", r.training);
  }

  const std::string target_units = join(r.target_units, ",");
  io.matrix("/test/predictions", r.test_predictions, target_units);
  io.matrix("/test/targets", r.test_targets, target_units);
}

// One training stage of a narx network. Files written before windows and
// second tries existed have no horizon (one window) and no fallback.
template <class Io, class St>
void narx_stage(Io& io, const std::string& g, St& st) {
  auto& s = st.summary;
  io.group(g);
  io.attr(g, "mode", st.mode);
  io.attr(g, "trainer", st.trainer);
  io.optional_attr(g, "horizon", st.horizon);
  io.optional_attr(g, "fallback", st.fallback);
  io.optional_attr(g, "fallback_horizon", st.fallback_horizon);
  io.choice(g, "termination", s.termination, parse_termination);
  io.attr(g, "message", s.message);
  io.attr(g, "best_epoch", s.best_epoch);
  io.attr(g, "beta_guard_count", s.beta_guard_count);
  epochs(io, g, s.history, "MSE in the dataset's target units");
  io.lm_history(g, s);
}

// A narx run (model.type narx): one network per target (/model/networks
// names their axes, e_x -> x; /model/<axis>/parameters, nn/narx.hpp), the
// stages of each (/history/<axis>/stage<k>), and the closed-loop prediction
// of the validation half (networks x steps; the first `first_step` steps are
// measured initial states). /training's trainer names the stages, e.g.
// "open_loop:TYPE+closed_loop:TYPE".
template <class Io, class R>
void narx(Io& io, R& r) {
  auto& n = *r.narx;
  auto& o = n.options;
  io.group("/model");
  io.note("/model", "type", "narx");
  io.attr("/model", "hidden", o.hidden);
  io.choice("/model", "activation", o.hidden_activation, parse_activation_name);
  io.attr("/model", "input_delays", o.input_delays);
  io.attr("/model", "feedback_delays", o.feedback_delays);
  io.attr("/model", "first_input_delay", o.first_input_delay);
  io.note("/model", "parameter_layout",
          o.inputs == 1 ? "per network: W1 (H x (D_V + D_E), column-major), b1 (H), W2 (1 x H), b2"
                        : "per network: W1 (H x (C D_V + D_E), column-major; C input channels, "
                          "each's delays together), b1 (H), W2 (1 x H), b2");
  auto networks = io.columns("/model", n.networks);
  networks.strings("networks", &NarxNetworkRecord::axis);
  networks.joined_strings("inputs", &NarxNetworkRecord::inputs, '+');  // e.g. v_x+direction_x
  networks.strings("targets", &NarxNetworkRecord::target);
  if constexpr (Io::reading) {
    // The channel count is not stored apart: every network's input list gives it.
    for (const auto& net : n.networks) {
      io.require(net.inputs.size() == n.networks.front().inputs.size(),
                 "/model/inputs: networks with different channel counts");
    }
    if (!n.networks.empty()) o.inputs = n.networks.front().inputs.size();
  }
  for (auto& net : n.networks) {
    io.vector("/model/" + net.axis + "/parameters", net.parameters, "1");
  }

  io.group("/training");
  io.attr("/training", "trainer", r.trainer);
  io.choice("/training", "termination", r.training.termination, parse_termination);
  io.attr("/training", "message", r.training.message);
  for (auto& net : n.networks) {
    const std::string g = "/history/" + net.axis;
    io.group(g);
    io.attr(g, "seconds", net.seconds);
    io.numbered_groups(g + "/stage", net.stages,
                       [&](const std::string& sg, auto& st) { narx_stage(io, sg, st); });
  }
  io.matrix("/validation/predictions", n.predictions, join(r.target_units, ","));
  io.matrix("/validation/targets", n.targets, join(r.target_units, ","));
  io.attr("/validation", "first_step", n.first_step);
}

// Everything of a training result but the header, metrics and upstream:
// /dataset, /split, then the model's parts (mlp, or narx when /model's type
// is "narx").
template <class Io, class R>
void training(Io& io, R& r) {
  io.group("/dataset");
  io.attr("/dataset", "file", r.dataset_file);
  io.attr("/dataset", "content_hash", r.dataset_hash);
  io.strings("/dataset/input_names", r.input_names);
  io.strings("/dataset/input_units", r.input_units);
  io.strings("/dataset/target_names", r.target_names);
  io.strings("/dataset/target_units", r.target_units);

  io.indices("/split/train", r.split.train);
  io.indices("/split/validation", r.split.validation);
  io.indices("/split/test", r.split.test);

  if (io.tagged_part("/model", "type", "narx", r.narx)) {
    narx(io, r);
  } else {
    mlp(io, r);
  }
}

}  // namespace cnclab::result_layout
