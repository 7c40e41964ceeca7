#include "cnclab/experiment/result_narx.hpp"

#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/experiment/result_lm_history.hpp"
#include "cnclab/io/eigen_std.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace {

void write_stage(H5File& f, const std::string& g, const NarxStageRecord& st) {
  const Summary& s = st.summary;
  f.create_group(g);
  f.set_attribute(g, "mode", st.mode);
  f.set_attribute(g, "trainer", st.trainer);
  f.set_attribute(g, "horizon", static_cast<std::int64_t>(st.horizon));
  f.set_attribute(g, "fallback", static_cast<std::int64_t>(st.fallback ? 1 : 0));
  f.set_attribute(g, "fallback_horizon", static_cast<std::int64_t>(st.fallback_horizon));
  f.set_attribute(g, "termination", to_string(s.termination));
  f.set_attribute(g, "message", s.message);
  f.set_attribute(g, "best_epoch", static_cast<std::int64_t>(s.best_epoch));
  f.set_attribute(g, "beta_guard_count", static_cast<std::int64_t>(s.beta_guard_count));
  std::vector<double> epoch, train, val, wall;
  for (const auto& e : s.history) {
    epoch.push_back(static_cast<double>(e.epoch));
    train.push_back(e.train_loss);
    val.push_back(e.validation_loss);
    wall.push_back(e.wall_seconds);
  }
  f.write_vector(g + "/epoch", epoch, "1");
  f.write_vector(g + "/train_loss", train, "MSE in the dataset's target units");
  f.write_vector(g + "/validation_loss", val, "MSE in the dataset's target units");
  f.write_vector(g + "/wall_seconds", wall, "s");
  write_lm_history(f, g, s);
}

NarxStageRecord read_stage(const H5File& f, const std::string& g) {
  const auto bad = [&](const std::string& what) {
    throw IoError(f.path().string() + ": " + g + ": " + what);
  };
  NarxStageRecord st;
  st.mode = f.attribute_string(g, "mode");
  st.trainer = f.attribute_string(g, "trainer");
  // Files written before windows existed have no horizon: one window.
  if (f.has_attribute(g, "horizon")) {
    st.horizon = static_cast<std::size_t>(f.attribute_int(g, "horizon"));
  }
  st.fallback = f.has_attribute(g, "fallback") && f.attribute_int(g, "fallback") != 0;
  if (f.has_attribute(g, "fallback_horizon")) {
    st.fallback_horizon = static_cast<std::size_t>(f.attribute_int(g, "fallback_horizon"));
  }
  Summary& s = st.summary;
  if (!parse_termination(f.attribute_string(g, "termination"), s.termination)) {
    bad("unknown termination");
  }
  s.message = f.attribute_string(g, "message");
  s.best_epoch = static_cast<std::size_t>(f.attribute_int(g, "best_epoch"));
  s.beta_guard_count = static_cast<std::size_t>(f.attribute_int(g, "beta_guard_count"));
  const auto epoch = f.read_vector(g + "/epoch");
  const auto train = f.read_vector(g + "/train_loss");
  const auto val = f.read_vector(g + "/validation_loss");
  const auto wall = f.read_vector(g + "/wall_seconds");
  if (train.size() != epoch.size() || val.size() != epoch.size() || wall.size() != epoch.size()) {
    bad("series of different lengths");
  }
  for (std::size_t i = 0; i < epoch.size(); ++i) {
    s.history.push_back({static_cast<std::size_t>(epoch[i]), train[i], val[i], wall[i]});
  }
  read_lm_history(f, g, epoch.size(), s);
  return st;
}

}  // namespace

void write_narx_sections(H5File& f, const RunRecord& r) {
  const NarxRecord& n = *r.narx;
  const NarxOptions& o = n.options;
  f.create_group("/model");
  f.set_attribute("/model", "type", "narx");
  f.set_attribute("/model", "hidden", static_cast<std::int64_t>(o.hidden));
  f.set_attribute("/model", "activation", to_string(o.hidden_activation));
  f.set_attribute("/model", "input_delays", static_cast<std::int64_t>(o.input_delays));
  f.set_attribute("/model", "feedback_delays", static_cast<std::int64_t>(o.feedback_delays));
  f.set_attribute("/model", "first_input_delay", static_cast<std::int64_t>(o.first_input_delay));
  f.set_attribute("/model", "parameter_layout",
                  o.inputs == 1
                      ? "per network: W1 (H x (D_V + D_E), column-major), b1 (H), W2 (1 x H), b2"
                      : "per network: W1 (H x (C D_V + D_E), column-major; C input channels, "
                        "each's delays together), b1 (H), W2 (1 x H), b2");
  std::vector<std::string> axes, inputs, targets;
  for (const auto& net : n.networks) {
    axes.push_back(net.axis);
    inputs.push_back(join(net.inputs, "+"));  // a network's channels, e.g. v_x+direction_x
    targets.push_back(net.target);
    f.write_vector("/model/" + net.axis + "/parameters", to_std(net.parameters), "1");
  }
  f.write_strings("/model/networks", axes);
  f.write_strings("/model/inputs", inputs);
  f.write_strings("/model/targets", targets);

  f.create_group("/training");
  f.set_attribute("/training", "trainer", r.trainer);
  f.set_attribute("/training", "termination", to_string(r.training.termination));
  f.set_attribute("/training", "message", r.training.message);
  for (const auto& net : n.networks) {
    const std::string g = "/history/" + net.axis;
    f.create_group(g);
    f.set_attribute(g, "seconds", net.seconds);
    for (std::size_t k = 0; k < net.stages.size(); ++k) {
      write_stage(f, g + "/stage" + std::to_string(k), net.stages[k]);
    }
  }
  f.write_matrix("/validation/predictions", n.predictions, join(r.target_units, ","));
  f.write_matrix("/validation/targets", n.targets, join(r.target_units, ","));
  f.set_attribute("/validation", "first_step", static_cast<std::int64_t>(n.first_step));
}

void read_narx_sections(const H5File& f, RunRecord& r) {
  NarxRecord n;
  NarxOptions& o = n.options;
  o.hidden = static_cast<std::size_t>(f.attribute_int("/model", "hidden"));
  try {
    o.hidden_activation = parse_activation(f.attribute_string("/model", "activation"));
  } catch (const OptionError& e) {
    throw IoError(f.path().string() + ": /model: " + e.what());
  }
  o.input_delays = static_cast<std::size_t>(f.attribute_int("/model", "input_delays"));
  o.feedback_delays = static_cast<std::size_t>(f.attribute_int("/model", "feedback_delays"));
  o.first_input_delay = static_cast<std::size_t>(f.attribute_int("/model", "first_input_delay"));
  const auto axes = f.read_strings("/model/networks");
  const auto inputs = f.read_strings("/model/inputs");
  const auto targets = f.read_strings("/model/targets");
  if (inputs.size() != axes.size() || targets.size() != axes.size()) {
    throw IoError(f.path().string() + ": /model: lists of different lengths");
  }
  for (std::size_t a = 0; a < axes.size(); ++a) {
    NarxNetworkRecord net;
    net.axis = axes[a];
    for (std::size_t from = 0;;) {
      const std::size_t plus = inputs[a].find('+', from);
      net.inputs.push_back(inputs[a].substr(from, plus - from));
      if (plus == std::string::npos) break;
      from = plus + 1;
    }
    if (a > 0 && net.inputs.size() != o.inputs) {
      throw IoError(f.path().string() + ": /model/inputs: networks with different channel counts");
    }
    o.inputs = net.inputs.size();
    net.target = targets[a];
    const auto p = f.read_vector("/model/" + net.axis + "/parameters");
    net.parameters =
        Eigen::Map<const Eigen::VectorXd>(p.data(), static_cast<Eigen::Index>(p.size()));
    const std::string g = "/history/" + net.axis;
    net.seconds = f.attribute_double(g, "seconds");
    for (std::size_t k = 0; f.exists(g + "/stage" + std::to_string(k)); ++k) {
      net.stages.push_back(read_stage(f, g + "/stage" + std::to_string(k)));
    }
    n.networks.push_back(std::move(net));
  }
  r.trainer = f.attribute_string("/training", "trainer");
  if (!parse_termination(f.attribute_string("/training", "termination"), r.training.termination)) {
    throw IoError(f.path().string() + ": /training: unknown termination");
  }
  r.training.message = f.attribute_string("/training", "message");
  n.predictions = f.read_matrix("/validation/predictions");
  n.targets = f.read_matrix("/validation/targets");
  n.first_step = static_cast<std::size_t>(f.attribute_int("/validation", "first_step"));
  r.narx = std::move(n);
}

void print_narx_model(const RunRecord& r, std::ostream& out) {
  const NarxRecord& n = *r.narx;
  const NarxOptions& o = n.options;
  out << "model        narx, one network per target: " << o.hidden << " "
      << to_string(o.hidden_activation) << " units, input delays " << o.first_input_delay << ".."
      << o.first_input_delay + o.input_delays - 1 << ", feedback delays 1.." << o.feedback_delays;
  if (!n.networks.empty()) out << " (" << n.networks[0].parameters.size() << " parameters each)";
  out << "\n";
  out << "training     " << r.trainer << ", " << to_string(r.training.termination) << "\n";
  for (const auto& net : n.networks) {
    out << "  " << net.axis << " (" << join(net.inputs, ", ") << " -> " << net.target << ", "
        << format_metric(net.seconds) << " s):";
    for (const auto& st : net.stages) {
      out << (st.fallback ? " second try: " : " ") << st.mode;
      if (st.horizon != 0) out << " (windows of " << st.horizon << " steps)";
      out << " " << st.trainer << " " << st.summary.history.size() << " epochs ("
          << to_string(st.summary.termination) << ")";
      const Summary& sm = st.summary;
      if (sm.lm_initial) out << " SSE " << format_metric(sm.lm_initial->sse) << " ->";
      if (!sm.lm_history.empty()) {
        out << (sm.lm_initial ? " " : " SSE ") << format_metric(sm.lm_history.back().sse);
      } else if (sm.lm_initial) {
        out << " (no step)";
      }
      out << ";";
    }
    out << "\n";
  }
}

}  // namespace cnclab
