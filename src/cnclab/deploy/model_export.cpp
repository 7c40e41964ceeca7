#include "cnclab/deploy/model_export.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/deploy/c_export.hpp"
#include "cnclab/deploy/float_bound.hpp"
#include "cnclab/deploy/prediction_input.hpp"
#include "cnclab/deploy/torch_export.hpp"
#include "cnclab/deploy/training_dataset.hpp"
#include "cnclab/io/atomic_file.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// The export's inputs over `samples` of the training dataset.
Eigen::MatrixXd export_inputs(const DeployedModel& m, const PredictionInput& data,
                              const std::vector<std::size_t>& samples) {
  const auto names = m.export_input_names();
  Eigen::MatrixXd x(static_cast<Eigen::Index>(names.size()),
                    static_cast<Eigen::Index>(samples.size()));
  for (std::size_t i = 0; i < names.size(); ++i) {
    const NamedColumn* c = data.find(names[i]);
    if (c == nullptr)
      throw Error(m.result_file + ": its training dataset has no column " + names[i]);
    for (std::size_t s = 0; s < samples.size(); ++s) {
      x(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(s)) =
          c->values[static_cast<Eigen::Index>(samples[s])];
    }
  }
  return x;
}

}  // namespace

std::vector<std::string> float_bound_statement(const DeployedModel& m,
                                               const TrainingDataOptions& data) {
  const PredictionInput d =
      dataset_input(training_dataset(m, data), InputKind::dataset_file, m.dataset_file);
  std::string part = "test split";
  const std::vector<std::size_t>* samples = &m.split.test;
  if (m.kind == ModelKind::narx) {
    part = "validation half";
    samples = &m.split.validation;
  } else if (samples->empty()) {
    part = m.split.validation.empty() ? "training split" : "validation split";
    samples = m.split.validation.empty() ? &m.split.train : &m.split.validation;
  }
  const Eigen::MatrixXd bound = float_error_bound(m, export_inputs(m, d, *samples));
  const auto names = m.export_output_names(), units = m.export_output_units();
  std::vector<std::string> lines = {
      "float bound |out_float - out_double| <= B: the running error bound of",
      "            src/cnclab/deploy/float_bound.hpp (u = 2^-24 + 2^-53, tanhf and expf",
      "            within 4 ulp), its largest value over the " + std::to_string(samples->size()) +
          " samples",
      "            of the " + part +
          (m.kind == ModelKind::narx ? " (closed loop from standstill):" : ":")};
  for (Eigen::Index k = 0; k < bound.rows(); ++k) {
    const auto i = static_cast<std::size_t>(k);
    lines.push_back("              " + names[i] +
                    ": B = " + shortest_double(bound.row(k).maxCoeff()) + " " + units[i]);
  }
  return lines;
}

ExportReport export_model(const fs::path& result_file, const ExportOptions& o) {
  if (o.format != "c" && o.format != "torch") {
    throw ConfigError("--format " + o.format + ": must be c (C99 for a controller) or torch");
  }
  const CPrecision precision = parse_precision(o.precision);
  if (o.format == "torch" && precision != CPrecision::float64) {
    throw ConfigError(
        "--precision float: the torch module takes its dtype when made, "
        "NAME(dtype=torch.float32); --precision is for --format c");
  }
  const DeployedModel m = load_deployed_model(result_file, o.data);
  const std::string name = o.name.empty() ? export_identifier(m.experiment) : o.name;
  check_export_identifier(name);
  ExportReport report;
  std::vector<std::pair<fs::path, std::string>> files;
  if (o.format == "c") {
    const std::vector<std::string> notes = precision == CPrecision::float32
                                               ? float_bound_statement(m, o.data)
                                               : std::vector<std::string>{};
    const CExport c = c_export(m, {name, precision}, notes);
    files = {{o.out_dir / (name + ".h"), c.header}, {o.out_dir / (name + ".c"), c.source}};
    report.lines = notes;
  } else {
    files = {{o.out_dir / (name + ".py"), torch_export(m, name)}};
  }
  for (const auto& [path, text] : files) {
    write_text_atomically(path, text);
    report.files.push_back(path);
  }
  std::string written;
  for (const auto& f : report.files) written += (written.empty() ? "" : ", ") + f.string();
  report.lines.insert(report.lines.begin(),
                      "wrote " + written + ": " + m.architecture() + ", " +
                          std::to_string(m.num_parameters()) + " parameters, " +
                          (o.format == "c" ? "C99 in " + to_string(precision) : "PyTorch module"));
  return report;
}

}  // namespace cnclab
