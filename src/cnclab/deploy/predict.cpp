#include "cnclab/deploy/predict.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/deploy/input_columns.hpp"
#include "cnclab/deploy/sequence_extension.hpp"

namespace cnclab {
namespace {

Eigen::VectorXd sample_indices(const std::vector<std::size_t>& samples) {
  Eigen::VectorXd v(static_cast<Eigen::Index>(samples.size()));
  for (std::size_t i = 0; i < samples.size(); ++i) {
    v[static_cast<Eigen::Index>(i)] = static_cast<double>(samples[i]);
  }
  return v;
}

void predict_mlp(const DeployedModel& m, const ModelColumns& in, Prediction& out) {
  const Mlp mlp(m.mlp);
  const Eigen::MatrixXd scaled = m.input_scaling.transform(in.inputs);
  const Eigen::MatrixXd y = m.target_scaling.inverse_transform(mlp.predict(m.parameters, scaled));
  for (std::size_t k = 0; k < m.num_outputs(); ++k) {
    const auto row = static_cast<Eigen::Index>(k);
    out.columns.push_back(
        {m.target_names[k] + ".predicted", m.target_units[k], y.row(row).transpose()});
    if (in.has_targets()) {
      out.columns.push_back(
          {m.target_names[k] + ".measured", m.target_units[k], in.targets.row(row).transpose()});
    }
  }
}

// The networks' series in the dataset's units, one per network.
struct NarxSeries {
  std::vector<Eigen::VectorXd> closed, open, measured;
};

// Closed loop from standstill: the series behind first_step() rest values
// (the physical 0 in the dataset's units, NarxPredictor::reset) so that
// every tick of the input is predicted.
Eigen::VectorXd closed_loop_from_rest(const Narx& narx, const DeployedModel& m, std::size_t a,
                                      const Eigen::VectorXd& v) {
  const Eigen::Index first = narx.first_step(), n = v.size();
  const double v_rest = m.has_physical_columns() ? m.physical_inputs[a].to_dataset(0.0) : 0.0;
  const double e_rest = m.has_physical_columns() ? m.physical_targets[a].to_dataset(0.0) : 0.0;
  Eigen::VectorXd padded_v(first + n), padded_e = Eigen::VectorXd::Constant(first + n, e_rest);
  padded_v.head(first).setConstant(v_rest);
  padded_v.tail(n) = v;
  return narx.simulate_closed_loop(m.networks[a].parameters, padded_v, padded_e);
}

NarxSeries predict_narx_series(const DeployedModel& m, const ModelColumns& in, bool from_rest) {
  const Narx narx(m.narx);
  const Eigen::Index first = narx.first_step(), n = in.inputs.cols();
  if (in.has_targets() && n <= first) {
    throw ConfigError("the input has " + std::to_string(n) +
                      " samples; the narx network needs more than " + std::to_string(first) +
                      " (its delays)");
  }
  NarxSeries s;
  for (std::size_t a = 0; a < m.networks.size(); ++a) {
    const auto row = static_cast<Eigen::Index>(a);
    const Eigen::VectorXd v = in.inputs.row(row).transpose();
    const Eigen::VectorXd& params = m.networks[a].parameters;
    if (from_rest) {
      s.closed.push_back(closed_loop_from_rest(narx, m, a, v));
    }
    if (!in.has_targets()) continue;
    const Eigen::VectorXd e = in.targets.row(row).transpose();
    s.measured.push_back(e);
    // The first first_step values are measured initial states (as the
    // result's stored validation prediction).
    Eigen::VectorXd open = e, closed = e;
    open.tail(n - first) =
        narx.mlp().predict(params, narx.open_loop_regressors(v, e)).row(0).transpose();
    s.open.push_back(std::move(open));
    if (!from_rest) {
      closed.tail(n - first) = narx.simulate_closed_loop(params, v, e);
      s.closed.push_back(std::move(closed));
    }
  }
  return s;
}

// The columns of one series (closed loop, open loop, measured); returns how
// many columns the extension added.
std::size_t add_narx_columns(const DeployedModel& m, const std::vector<Eigen::VectorXd>& series,
                             const std::string& label, const ModelColumns& in, Prediction& out) {
  if (series.empty()) return 0;
  std::vector<Eigen::VectorXd> physical;
  for (std::size_t a = 0; a < series.size(); ++a) {
    out.columns.push_back({m.target_names[a] + "." + label, m.target_units[a], series[a]});
  }
  if (!m.has_physical_columns()) return 0;
  for (std::size_t a = 0; a < series.size(); ++a) {
    const ColumnScaling& c = m.physical_targets[a];
    Eigen::VectorXd x = series[a].unaryExpr([&](double y) { return c.to_physical(y); });
    out.columns.push_back({c.name + "." + label, c.unit, x});
    physical.push_back(std::move(x));
  }
  if (m.extension == nullptr || !m.extension->per_tick) return 0;
  auto extra = m.extension->per_tick(m, in.context, physical, label);
  for (auto& column : extra) out.columns.push_back(std::move(column));
  return extra.size();
}

void predict_narx(const DeployedModel& m, const ModelColumns& in, InitialState initial,
                  Prediction& out) {
  if (initial == InitialState::measured && !in.has_targets()) {
    throw ConfigError(
        "--initial measured: the input has no measured target columns to start from (--initial "
        "rest starts from standstill)");
  }
  const bool from_rest = initial == InitialState::rest || !in.has_targets();
  const NarxSeries s = predict_narx_series(m, in, from_rest);
  out.initial_state = from_rest ? "rest" : "measured";
  out.first_step = from_rest ? 0 : static_cast<std::size_t>(Narx(m.narx).first_step());
  const std::size_t extra = add_narx_columns(m, s.closed, "closed_loop", in, out) +
                            add_narx_columns(m, s.open, "open_loop", in, out) +
                            add_narx_columns(m, s.measured, "measured", in, out);
  out.notes.push_back(
      from_rest ? "closed loop from standstill (every past input and output the physical 0)"
                : "closed and open loop from the first " + std::to_string(out.first_step) +
                      " measured samples (those rows repeat them)");
  if (!in.has_targets()) out.notes.push_back("no open loop: it feeds back measured values");
  if (m.has_physical_columns() && m.extension != nullptr && extra == 0) {
    std::vector<std::string> context;
    for (const auto& [name, unit] : m.extension->context_columns) context.push_back(name);
    out.notes.push_back("no per-tick " + m.extension->owner +
                        " columns: they need the input's columns " + join(context, ", "));
  }
}

}  // namespace

InitialState parse_initial_state(const std::string& text) {
  if (text == "measured") return InitialState::measured;
  if (text == "rest") return InitialState::rest;
  throw ConfigError("--initial " + text + ": must be measured or rest");
}

Prediction predict(const DeployedModel& m, const PredictionInput& input,
                   const PredictOptions& options) {
  if (m.kind == ModelKind::mlp && options.initial != InitialState::automatic) {
    throw ConfigError("--initial: a narx option; " + m.result_file + " holds an mlp");
  }
  const ModelColumns in = model_columns(m, input, options.split);
  Prediction out;
  out.samples = in.samples.size();
  out.notes = in.notes;
  out.columns.push_back({"sample", "1", sample_indices(in.samples)});
  if (m.kind == ModelKind::mlp) {
    predict_mlp(m, in, out);
  } else {
    predict_narx(m, in, options.initial, out);
  }
  return out;
}

}  // namespace cnclab
