#include "cnclab/deploy/deployed_model.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/deploy/sequence_extension.hpp"
#include "cnclab/deploy/training_dataset.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/upstream.hpp"

namespace cnclab {
namespace {

void check_parameters(const Eigen::VectorXd& p, std::size_t expected, const std::string& what,
                      const std::string& file) {
  if (p.size() != static_cast<Eigen::Index>(expected)) {
    throw ConfigError(file + ": " + what + " has " + std::to_string(p.size()) +
                      " parameters, its network " + std::to_string(expected));
  }
  if (!p.allFinite()) throw ConfigError(file + ": " + what + " has NaN or infinite parameters");
}

std::string generator_of(const RunRecord& r, const std::string& file) {
  // The generator names itself in the dataset section of the resolved config.
  const ConfigDocument doc = ConfigDocument::parse(r.resolved_yaml, file + ": /config");
  const ConfigReader root = doc.root();
  if (!root.has("dataset")) throw ConfigError(file + ": /config has no dataset section");
  return root.section("dataset").require<std::string>("generator");
}

std::vector<std::string> physical_field(const std::vector<ColumnScaling>& columns, bool units) {
  std::vector<std::string> out;
  for (const auto& c : columns) out.push_back(units ? c.unit : c.name);
  return out;
}

}  // namespace

std::string to_string(ModelKind kind) {
  return kind == ModelKind::mlp ? "mlp" : "narx";
}

std::size_t DeployedModel::num_parameters() const {
  if (kind == ModelKind::mlp) return static_cast<std::size_t>(parameters.size());
  std::size_t n = 0;
  for (const auto& net : networks) n += static_cast<std::size_t>(net.parameters.size());
  return n;
}

std::vector<std::string> DeployedModel::export_input_names() const {
  return has_physical_columns() ? physical_field(physical_inputs, false) : input_names;
}
std::vector<std::string> DeployedModel::export_input_units() const {
  return has_physical_columns() ? physical_field(physical_inputs, true) : input_units;
}
std::vector<std::string> DeployedModel::export_output_names() const {
  return has_physical_columns() ? physical_field(physical_targets, false) : target_names;
}
std::vector<std::string> DeployedModel::export_output_units() const {
  return has_physical_columns() ? physical_field(physical_targets, true) : target_units;
}

std::string DeployedModel::architecture() const {
  if (kind == ModelKind::mlp) {
    std::string s = "mlp " + std::to_string(mlp.inputs);
    for (auto h : mlp.hidden) {
      s += '-';  // appended: `"-" + std::to_string` makes GCC 12 warn falsely (PR105329)
      s += std::to_string(h);
    }
    return s + "-" + std::to_string(mlp.outputs) + " (" + to_string(mlp.hidden_activation) +
           " hidden, " + to_string(mlp.output_activation) + " output)";
  }
  return "narx, " + std::to_string(networks.size()) + " network(s) of " +
         std::to_string(narx.hidden) + " " + to_string(narx.hidden_activation) +
         " units, input delays " + std::to_string(narx.first_input_delay) + ".." +
         std::to_string(narx.first_input_delay + narx.input_delays - 1) + ", feedback delays 1.." +
         std::to_string(narx.feedback_delays);
}

DeployedModel deployed_model(const RunRecord& r, const std::string& file) {
  if (r.kind != "train") {
    throw ConfigError(file + ": the result of a `kind: " + r.kind +
                      "` job, not a trained network; predict and export need a training result");
  }
  if (r.provenance.status != "complete") {
    throw ConfigError(file + ": its training failed (" + r.provenance.failure_reason +
                      "); there is no trained network to use");
  }
  DeployedModel m;
  m.result_file = file;
  m.experiment = r.experiment;
  m.identity = result_identity(r);
  m.config_hash = r.config_hash;
  m.trained_utc = r.provenance.end_utc;
  m.cnclab_version = r.provenance.cnclab_version;
  m.git_commit = r.provenance.git_commit;
  m.generator = generator_of(r, file);
  m.dataset_file = r.dataset_file;
  m.dataset_hash = r.dataset_hash;
  const auto seed = r.provenance.derived_seeds.find("generator");
  if (seed == r.provenance.derived_seeds.end()) {
    throw ConfigError(file + ": /provenance has no generator seed");
  }
  m.generator_seed = seed->second;
  m.resolved_yaml = r.resolved_yaml;
  m.metrics = r.metrics;
  m.metric_units = r.metric_units;
  m.input_names = r.input_names;
  m.input_units = r.input_units;
  m.target_names = r.target_names;
  m.target_units = r.target_units;
  m.split = r.split;
  if (!r.narx) {
    m.kind = ModelKind::mlp;
    m.mlp = r.model;
    m.parameters = r.parameters;
    m.input_scaling = r.input_scaling;
    m.target_scaling = r.target_scaling;
    check_parameters(m.parameters, Mlp(m.mlp).num_parameters(), "the network", file);
    if (m.mlp.inputs != m.input_names.size() || m.mlp.outputs != m.target_names.size()) {
      throw ConfigError(file + ": the network's " + std::to_string(m.mlp.inputs) + " inputs and " +
                        std::to_string(m.mlp.outputs) + " outputs do not match its " +
                        std::to_string(m.input_names.size()) + " input and " +
                        std::to_string(m.target_names.size()) + " target columns");
    }
    return m;
  }
  m.kind = ModelKind::narx;
  m.narx = r.narx->options;
  const Narx narx(m.narx);
  for (const auto& net : r.narx->networks) {
    // Seed 002's networks: one input channel each (model.inputs absent).
    if (net.inputs.size() != 1) {
      throw ConfigError(file + ": network " + net.axis + " has " +
                        std::to_string(net.inputs.size()) + " input channels (" +
                        join(net.inputs, ", ") +
                        "); predict and export take one input channel per narx network");
    }
  }
  if (r.narx->networks.size() != m.target_names.size() ||
      m.input_names.size() != m.target_names.size()) {
    throw ConfigError(file + ": " + std::to_string(r.narx->networks.size()) +
                      " narx networks for " + std::to_string(m.target_names.size()) + " targets");
  }
  for (const auto& net : r.narx->networks) {
    check_parameters(net.parameters, narx.num_parameters(), "network " + net.axis, file);
    m.networks.push_back({net.axis, net.inputs.front(), net.target, net.parameters});
  }
  m.extension = find_sequence_extension(m.generator);
  return m;
}

DeployedModel load_deployed_model(const std::filesystem::path& result_file,
                                  const TrainingDataOptions& data) {
  DeployedModel m = deployed_model(read_result(result_file), result_file.string());
  if (m.kind == ModelKind::narx && m.extension != nullptr) {
    m.extension->physical_columns(training_dataset(m, data), m);
  }
  return m;
}

}  // namespace cnclab
