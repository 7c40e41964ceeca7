#include "cnclab/deploy/prediction_input.hpp"

#include <fstream>
#include <iostream>
#include <sstream>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/core/override.hpp"
#include "cnclab/core/progress.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/data/dataset_file.hpp"
#include "cnclab/data/dataset_spec.hpp"
#include "cnclab/deploy/csv_table.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

InputKind kind_of(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".h5" || ext == ".hdf5") return InputKind::dataset_file;
  if (ext == ".yaml" || ext == ".yml") return InputKind::dataset_config;
  if (ext == ".csv") return InputKind::csv;
  throw ConfigError(file.string() +
                    ": unknown input (a dataset .h5, a dataset config .yaml or raw inputs .csv)");
}

void add_rows(const Eigen::MatrixXd& m, const std::vector<std::string>& names,
              const std::vector<std::string>& units, std::vector<NamedColumn>& out) {
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    out.push_back({names[k], units[k], m.row(i).transpose()});
  }
}

}  // namespace

PredictionInput dataset_input(const Dataset& d, InputKind kind, const std::string& source) {
  PredictionInput in;
  in.kind = kind;
  in.source = source;
  in.hash = d.content_hash();
  in.generator = d.generator;
  in.samples = d.num_samples();
  add_rows(d.inputs, d.input_names, d.input_units, in.columns);
  add_rows(d.targets, d.target_names, d.target_units, in.columns);
  if (d.has_metadata()) add_rows(d.metadata, d.metadata_names, d.metadata_units, in.columns);
  return in;
}

namespace {

// The dataset a config's `dataset:` section describes (as `cnclab dataset
// generate` reads it: the generator seed is dataset.seed, else derived from
// the file's `seed`), through the dataset cache.
Dataset config_dataset(const fs::path& file, const InputOptions& o) {
  ConfigDocument doc = ConfigDocument::load(file);
  for (const auto& text : o.overrides) doc.apply(parse_override(text));
  const ConfigReader root = doc.root();
  if (!root.has("dataset")) root.fail("dataset", "is required to predict on a config");
  const DatasetSpec spec = read_dataset_spec(root.section("dataset"));
  const auto master = root.optional<std::uint64_t>("seed");
  const std::uint64_t seed =
      spec.seed ? *spec.seed : (master ? derive_seed(*master, "generator") : 0);
  StagedProgress progress("dataset " + spec.generator->name(), o.log ? *o.log : std::cerr,
                          {o.log ? ProgressMode::automatic : ProgressMode::quiet, 5.0, 0.1});
  return obtain_dataset(spec, seed, o.data_dir, o.log, false, progress.callback()).dataset;
}

std::string file_hash(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return hash_hex(bytes.str());
}

}  // namespace

std::string to_string(InputKind kind) {
  switch (kind) {
    case InputKind::dataset_file:
      return "dataset";
    case InputKind::dataset_config:
      return "dataset config";
    case InputKind::csv:
      break;
  }
  return "csv";
}

const NamedColumn* PredictionInput::find(const std::string& name) const {
  for (const auto& c : columns) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

PredictionInput read_prediction_input(const fs::path& file, const InputOptions& o) {
  const InputKind kind = kind_of(file);
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) throw ConfigError(file.string() + ": no such file");
  if (fs::file_size(file, ec) == 0) throw ConfigError(file.string() + ": empty file");
  if (kind != InputKind::dataset_config && !o.overrides.empty()) {
    throw ConfigError("overrides (" + o.overrides.front() +
                      ") apply to a dataset config (.yaml) only, not to " + file.string());
  }
  PredictionInput in;
  if (kind == InputKind::dataset_file) {
    in = dataset_input(read_dataset(file), kind, file.string());
  } else if (kind == InputKind::dataset_config) {
    in = dataset_input(config_dataset(file, o), kind, file.string());
  } else {
    in.kind = kind;
    in.source = file.string();
    in.hash = file_hash(file);
    in.columns = read_csv_table(file);
    in.samples = static_cast<std::size_t>(in.columns.front().values.size());
  }
  if (in.samples == 0) throw ConfigError(file.string() + ": no samples");
  return in;
}

}  // namespace cnclab
