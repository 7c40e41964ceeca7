#include "cnclab/experiment/spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/core/suggest.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/experiment/spec_narx.hpp"
#include "cnclab/experiment/spec_text.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace {

Scaling read_scaling(const ConfigReader& r, const std::string& key) {
  Scaling s = Scaling::zscore;
  parse_scaling(choice(r, key, to_string(s), {"zscore", "minmax", "none"}), s);
  return s;
}

std::array<double, 2> read_range(const ConfigReader& r, const std::string& key,
                                 std::array<double, 2> fallback) {
  if (!r.has(key)) return fallback;
  const auto v = r.require<std::vector<double>>(key);
  if (v.size() != 2 || !(v[0] < v[1])) r.fail(key, "must be a list [low, high] with low < high");
  return {v[0], v[1]};
}

Activation read_activation(const ConfigReader& r, const std::string& key, Activation fallback) {
  const auto text = r.get<std::string>(key, to_string(fallback));
  try {
    return parse_activation(text);
  } catch (const Error&) {
    const std::vector<std::string> names = {"relu", "tanh", "sigmoid", "linear"};
    r.fail(key, one_of(names) + did_you_mean(text, names));
  }
}

Initializer read_initializer(const ConfigReader& r, const Initializer& fallback) {
  Initializer init = fallback;
  const auto kind =
      choice(r, "type", to_string(fallback.kind), {"normal", "uniform", "xavier", "he"});
  init.kind = kind == "normal"    ? Initializer::Kind::normal
              : kind == "uniform" ? Initializer::Kind::uniform
              : kind == "xavier"  ? Initializer::Kind::xavier
                                  : Initializer::Kind::he;
  if (init.kind == Initializer::Kind::normal) {
    init.mean = r.get<double>("mean", init.mean);
    init.std = r.get<double>("std", init.std);
  } else if (init.kind == Initializer::Kind::uniform) {
    init.low = r.get<double>("low", init.low);
    init.high = r.get<double>("high", init.high);
  }
  r.validate([&] { init.validate(); });
  return init;
}

// "; the fragments in configs/<group>/ provide one: a.yaml, b.yaml" for the
// nearest configs/<group>/ in `base` or an ancestor of it ("" when none).
std::string fragment_hint(const std::filesystem::path& base, const std::string& group) {
  std::error_code ec;
  const auto start = std::filesystem::absolute(base, ec);
  if (ec) return "";
  for (auto dir = start;; dir = dir.parent_path()) {
    const auto folder = dir / "configs" / group;
    if (std::filesystem::is_directory(folder, ec)) {
      std::vector<std::string> names;
      for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
        if (entry.path().extension() == ".yaml") names.push_back(entry.path().filename().string());
      }
      std::sort(names.begin(), names.end());
      if (names.empty()) return "";
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      return "; the fragments in " + (std::filesystem::path("configs") / group).string() +
             "/ provide one (include: configs/" + group + "/NAME.yaml): " + list;
    }
    if (dir == dir.parent_path()) break;
  }
  return "";
}

// Config groups (Hydra-style): `trainer=NAME`, `dataset=NAME`, `model=NAME`
// with a plain name replace the whole block by the one in
// configs/<group>s/NAME.yaml (found as `include:` finds configs/...).
// Any other override is returned unchanged.
Override expand_config_group(const Override& o, const std::filesystem::path& base) {
  static const std::vector<std::string> kGroups = {"trainer", "dataset", "model"};
  if (o.path.size() != 1 || !o.value.IsScalar() ||
      std::find(kGroups.begin(), kGroups.end(), o.path[0]) == kGroups.end()) {
    return o;
  }
  const std::string& group = o.path[0];
  const std::string name = "configs/" + group + "s/" + o.value.Scalar() + ".yaml";
  const std::filesystem::path file = resolve_config_path(base / "experiment.yaml", name);
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw ConfigError("override " + o.text + ": no config group file " + name + " (looked in " +
                      base.string() + " and the configs/ folders above it)" +
                      fragment_hint(base, group + "s"));
  }
  const ConfigDocument fragment = ConfigDocument::load(file);
  const YAML::Node block = YAML::Load(fragment.to_yaml())[group];
  if (!block.IsMap()) {
    throw ConfigError("override " + o.text + ": " + file.string() + " has no `" + group +
                      ":` block");
  }
  // A new Override: assigning to o's copied YAML::Node would rewrite o's node.
  return Override{o.path, block, o.text};
}

// What an experiment is about has no default (README: "never a silent
// default"): a forgotten dataset include must not train on some built-in
// data set. The dataset generator, the model block and the trainer type are
// required; everything inside them keeps the defaults of the key table.
void require_subject(const ConfigReader& root, const std::filesystem::path& base) {
  if (!root.section("dataset").has("generator")) {
    root.section("dataset").fail("generator", "is required (what data the experiment learns)" +
                                                  fragment_hint(base, "datasets"));
  }
  if (!root.has("model")) {
    root.fail("model", "is required (the network, e.g. model: {type: mlp, hidden: [28, 20]})");
  }
  if (!root.section("trainer").has("type") && !root.section("trainer").has("stages")) {
    root.section("trainer").fail(
        "type", "is required (sgdm, lm or trainbr)" + fragment_hint(base, "trainers"));
  }
}

SplitOptions read_split(const ConfigReader& r, std::size_t samples) {
  SplitOptions s;
  if (choice(r, "mode", "random", {"random", "sequential_halves"}) == "sequential_halves") {
    s.mode = SplitMode::sequential_halves;
    for (const auto& key : r.keys()) {
      if (key != "mode") r.fail(key, "applies to split.mode random only");
    }
    return s;
  }
  s.train_count = r.optional<std::size_t>("train_count");
  s.validation_count = r.optional<std::size_t>("validation_count");
  s.test_count = r.optional<std::size_t>("test_count");
  if (s.train_count || s.validation_count || s.test_count) {
    for (const char* key : {"train", "validation"}) {
      if (r.has(key)) r.fail(key, "give either fractions (train, validation) or counts, not both");
    }
  }
  s.train_fraction = r.get<double>("train", s.train_fraction);
  s.validation_fraction = r.get<double>("validation", s.validation_fraction);
  r.validate([&] {
    try {
      s.validate_for(samples);
    } catch (const OptionError& e) {
      // SplitOptions names its fields *_fraction; the YAML keys are shorter.
      const std::string key = e.field() == "train_fraction"        ? "train"
                              : e.field() == "validation_fraction" ? "validation"
                                                                   : e.field();
      throw OptionError(key, e.value(), e.rule());
    }
  });
  return s;
}

MlpOptions read_model(const ConfigReader& r) {
  MlpOptions m;
  choice(r, "type", "mlp", {"mlp"});
  m.hidden = r.get<std::vector<std::size_t>>("hidden", m.hidden);
  m.hidden_activation = read_activation(r, "hidden_activation", m.hidden_activation);
  m.output_activation = read_activation(r, "output_activation", m.output_activation);
  const ConfigReader d = r.section("dropout");
  m.dropout_keep_probability = d.get<double>("keep_probability", m.dropout_keep_probability);
  const auto placement = choice(d, "placement", to_string(m.dropout_placement),
                                {"between_hidden", "after_every_hidden"});
  m.dropout_placement = placement == "between_hidden" ? DropoutPlacement::between_hidden
                                                      : DropoutPlacement::after_every_hidden;
  const ConfigReader init = r.section("init");
  m.weights = read_initializer(init.section("weights"), m.weights);
  m.biases = read_initializer(init.section("biases"), m.biases);
  // inputs/outputs are set from the dataset; validate the rest with
  // placeholders so a bad value is reported now, not after generation.
  MlpOptions check = m;
  check.inputs = 1;
  check.outputs = 1;
  r.validate([&] {
    try {
      check.validate();
    } catch (const OptionError& e) {
      const std::string key = e.field() == "dropout_keep_probability" ? "dropout.keep_probability"
                              : e.field() == "dropout_placement"      ? "dropout.placement"
                                                                      : e.field();
      throw OptionError(key, e.value(), e.rule());
    }
  });
  return m;
}

void read_graph(const ConfigReader& root, const std::filesystem::path& base, ExperimentSpec& spec) {
  spec.needs = root.get<std::vector<std::string>>("needs", {});
  for (const auto& text : spec.needs) {
    spec.needs_files.push_back(upstream_file(root, "needs", text, base));
  }
  if (root.has("init_from")) {
    const ConfigReader init = root.section("init_from");
    InitFromSpec from;
    from.experiment = init.require<std::string>("experiment");
    from.resolved_file = upstream_file(init, "experiment", from.experiment, base);
    from.normaliser =
        choice(init, "normaliser", to_string(from.normaliser), {"refit", "keep"}) == "keep"
            ? NormaliserSource::keep
            : NormaliserSource::refit;
    spec.init_from = from;
  }
  // The sweep block is read by `cnclab sweep` (sweep_spec.hpp); a run of the
  // file runs its base configuration.
  root.raw("sweep");
}

// The training part must be trainable: at least 2 samples, unless
// trainer.epochs is 0 (evaluation only). With no training samples nothing can
// be fitted, so the normaliser must come from init_from (keep) or be none.
void check_training_samples(const ConfigReader& root, const ExperimentSpec& spec) {
  const std::size_t n_train = spec.split.sizes(spec.dataset.generator->shape().samples).train;
  const ConfigReader split = root.section("split");
  const std::string key = spec.split.uses_counts() ? "train_count" : "train";
  if (trainer_epochs(spec.trainer) > 0 && n_train < 2) {
    split.fail(key, "leaves " + std::to_string(n_train) +
                        " training samples; at least 2 are needed to train (trainer.epochs: 0 "
                        "evaluates the starting network without training)");
  }
  const bool keeps = spec.init_from && spec.init_from->normaliser == NormaliserSource::keep;
  const bool nothing_to_fit =
      spec.normalisation.inputs == Scaling::none && spec.normalisation.targets == Scaling::none;
  if (n_train == 0 && !keeps && !nothing_to_fit) {
    split.fail(key,
               "leaves no training samples to fit the normaliser on; use "
               "init_from: {experiment: ..., normaliser: keep} (or normalisation none)");
  }
}

LoadedExperiment read_experiment(ConfigDocument& doc, const std::vector<Override>& overrides,
                                 std::optional<std::uint64_t> seed_override,
                                 const std::filesystem::path& base) {
  // Config groups first, then the other overrides, whatever their order on
  // the command line (as Hydra's defaults list): `trainer=trainbr
  // trainer.epochs=5` and `trainer.epochs=5 trainer=trainbr` both train 5.
  std::vector<Override> groups, rest;
  for (const auto& override : overrides) {
    Override expanded = expand_config_group(override, base);
    const bool group = expanded.value.IsMap() && !override.value.IsMap();
    (group ? groups : rest).push_back(std::move(expanded));
  }
  for (const auto& override : groups) doc.apply(override);
  for (const auto& override : rest) doc.apply(override);
  if (seed_override) doc.apply(parse_override("seed=" + std::to_string(*seed_override)));

  const ConfigReader root = doc.root();
  ExperimentSpec spec;
  if (root.get<std::string>("kind", "train") != "train") {
    root.fail("kind",
              "must be train here (other kinds are read by their job, experiment/job_kinds.hpp)");
  }
  spec.name = read_experiment_name(root);
  spec.description = root.get<std::string>("description", "");
  spec.seed = root.require<std::uint64_t>("seed");
  require_subject(root, base);
  spec.dataset = read_dataset_spec(root.section("dataset"));
  spec.split = read_split(root.section("split"), spec.dataset.generator->shape().samples);
  const ConfigReader norm = root.section("normalisation");
  spec.normalisation.inputs = read_scaling(norm, "inputs");
  spec.normalisation.targets = read_scaling(norm, "targets");
  for (const auto& [key, scaling] : {std::pair{"input_range", spec.normalisation.inputs},
                                     std::pair{"target_range", spec.normalisation.targets}}) {
    if (norm.has(key) && scaling != Scaling::minmax) norm.fail(key, "applies to minmax only");
  }
  spec.normalisation.input_range = read_range(norm, "input_range", spec.normalisation.input_range);
  spec.normalisation.target_range =
      read_range(norm, "target_range", spec.normalisation.target_range);
  std::vector<std::string> notes;
  if (read_model_type(root.section("model")) == "narx") {
    read_narx_experiment(root, spec);
  } else {
    spec.model = read_model(root.section("model"));
    spec.trainer = read_trainer(root.section("trainer"), &notes);
  }
  if (is_levenberg_marquardt(spec.trainer) && spec.model.dropout_keep_probability < 1.0) {
    root.section("model").section("dropout").fail(
        "keep_probability", "must be 1 with trainer " + trainer_name(spec.trainer) +
                                " (Levenberg-Marquardt needs a deterministic network)");
  }
  spec.metrics = root.get<std::vector<std::string>>(
      "metrics", spec.narx ? sequence_metric_names() : spec.metrics);
  for (const auto& m : spec.metrics) {
    const auto known = spec.narx ? sequence_metric_names() : known_metrics();
    if (std::find(known.begin(), known.end(), m) == known.end()) {
      root.fail("metrics",
                "unknown metric '" + m + "'" + did_you_mean(m, known) + "; " + one_of(known));
    }
  }
  read_graph(root, base, spec);
  spec.may_diverge = root.get<bool>("may_diverge", false);
  check_training_samples(root, spec);
  doc.check_all_consumed();
  return {spec, to_yaml(spec), notes};
}

void emit_initializer(YAML::Emitter& out, const Initializer& init) {
  out << YAML::BeginMap << YAML::Key << "type" << YAML::Value << to_string(init.kind);
  if (init.kind == Initializer::Kind::normal) {
    out << YAML::Key << "mean" << YAML::Value << shortest_double(init.mean);
    out << YAML::Key << "std" << YAML::Value << shortest_double(init.std);
  } else if (init.kind == Initializer::Kind::uniform) {
    out << YAML::Key << "low" << YAML::Value << shortest_double(init.low);
    out << YAML::Key << "high" << YAML::Value << shortest_double(init.high);
  }
  out << YAML::EndMap;
}

void emit_mlp_model(YAML::Emitter& out, const MlpOptions& m) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  out << Key << "model" << Value << BeginMap;
  out << Key << "type" << Value << "mlp";
  out << Key << "hidden" << Value << YAML::Flow << m.hidden;
  out << Key << "hidden_activation" << Value << to_string(m.hidden_activation);
  out << Key << "output_activation" << Value << to_string(m.output_activation);
  out << Key << "dropout" << Value << BeginMap;
  out << Key << "keep_probability" << Value << shortest_double(m.dropout_keep_probability);
  out << Key << "placement" << Value << to_string(m.dropout_placement);
  out << EndMap;
  out << Key << "init" << Value << BeginMap;
  out << Key << "weights" << Value;
  emit_initializer(out, m.weights);
  out << Key << "biases" << Value;
  emit_initializer(out, m.biases);
  out << EndMap << EndMap;
}

std::vector<Override> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<Override> out;
  for (const auto& text : texts) out.push_back(parse_override(text));
  return out;
}

}  // namespace

std::filesystem::path upstream_file(const ConfigReader& r, const std::string& key,
                                    const std::string& text, const std::filesystem::path& base) {
  const std::filesystem::path path =
      std::filesystem::path(text).is_absolute() ? std::filesystem::path(text) : base / text;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    r.fail(key, "no experiment file " + path.string());
  }
  return path.lexically_normal();
}

std::string to_string(NormaliserSource s) {
  return s == NormaliserSource::keep ? "keep" : "refit";
}

std::string read_experiment_name(const ConfigReader& root) {
  const auto name = root.require<std::string>("name");
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-' || c == '.';
    if (!ok || name.front() == '.') {
      root.fail("name", "must be a file-name-safe identifier (letters, digits, '_', '-', '.')");
    }
  }
  return name;
}

LoadedExperiment load_experiment(const std::filesystem::path& file,
                                 const std::vector<Override>& overrides,
                                 std::optional<std::uint64_t> seed_override,
                                 const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  LoadedExperiment loaded = read_experiment(doc, overrides, seed_override, file.parent_path());
  loaded.spec.source_file = file;
  loaded.spec.profile = profile;
  return loaded;
}

LoadedExperiment load_experiment(const std::filesystem::path& file,
                                 const std::vector<std::string>& overrides,
                                 std::optional<std::uint64_t> seed_override,
                                 const std::string& profile) {
  return load_experiment(file, parse_overrides(overrides), seed_override, profile);
}

LoadedExperiment parse_experiment(const std::string& yaml_text, const std::string& origin,
                                  const std::vector<std::string>& overrides) {
  ConfigDocument doc = ConfigDocument::parse(yaml_text, origin);
  return read_experiment(doc, parse_overrides(overrides), std::nullopt, ".");
}

std::vector<std::filesystem::path> upstream_files(const ExperimentSpec& spec) {
  std::vector<std::filesystem::path> out = spec.needs_files;
  if (spec.init_from) out.push_back(spec.init_from->resolved_file);
  std::vector<std::filesystem::path> unique;
  for (const auto& p : out) {
    if (std::find(unique.begin(), unique.end(), p) == unique.end()) unique.push_back(p);
  }
  return unique;
}

std::uint64_t generator_seed(const ExperimentSpec& spec) {
  return spec.dataset.seed ? *spec.dataset.seed : derive_seed(spec.seed, "generator");
}

std::string to_yaml(const ExperimentSpec& spec) {
  using YAML::Key, YAML::Value, YAML::BeginMap, YAML::EndMap;
  YAML::Emitter out;
  out << BeginMap;
  out << Key << "name" << Value << spec.name;
  out << Key << "description" << Value << spec.description;
  out << Key << "seed" << Value << spec.seed;

  out << Key << "dataset" << Value << BeginMap;
  out << Key << "generator" << Value << spec.dataset.generator->name();
  if (spec.dataset.seed) out << Key << "seed" << Value << *spec.dataset.seed;
  if (!spec.dataset.targets.empty()) {
    out << Key << "targets" << Value << YAML::Flow << spec.dataset.targets;
  }
  out << Key << "options" << Value << YAML::Load(spec.dataset.generator->options_yaml());
  out << EndMap;

  const SplitOptions& split = spec.split;
  out << Key << "split" << Value << BeginMap;
  if (split.mode == SplitMode::sequential_halves) {
    out << Key << "mode" << Value << "sequential_halves";
  } else if (split.uses_counts()) {
    out << Key << "train_count" << Value << *split.train_count;
    if (split.validation_count)
      out << Key << "validation_count" << Value << *split.validation_count;
    if (split.test_count) out << Key << "test_count" << Value << *split.test_count;
  } else {
    out << Key << "train" << Value << shortest_double(split.train_fraction);
    out << Key << "validation" << Value << shortest_double(split.validation_fraction);
  }
  out << EndMap;

  const NormalisationSpec& norm = spec.normalisation;
  const auto range = [](const std::array<double, 2>& r) {
    return std::vector<std::string>{shortest_double(r[0]), shortest_double(r[1])};
  };
  out << Key << "normalisation" << Value << BeginMap;
  out << Key << "inputs" << Value << to_string(norm.inputs);
  out << Key << "targets" << Value << to_string(norm.targets);
  if (norm.inputs == Scaling::minmax) {
    out << Key << "input_range" << Value << YAML::Flow << range(norm.input_range);
  }
  if (norm.targets == Scaling::minmax) {
    out << Key << "target_range" << Value << YAML::Flow << range(norm.target_range);
  }
  out << EndMap;

  if (spec.narx) {
    out << Key << "model" << Value;
    emit_narx_model(out, *spec.narx);
  } else {
    emit_mlp_model(out, spec.model);
  }
  out << Key << "trainer" << Value;
  if (spec.narx) {
    emit_stages(out, spec.stages);
  } else {
    emit_trainer(out, spec.trainer);
  }

  out << Key << "metrics" << Value << YAML::Flow << spec.metrics;
  // Emitted only when set, so experiments without them keep their identity.
  if (!spec.needs.empty()) out << Key << "needs" << Value << YAML::Flow << spec.needs;
  if (spec.init_from) {
    out << Key << "init_from" << Value << BeginMap;
    out << Key << "experiment" << Value << spec.init_from->experiment;
    out << Key << "normaliser" << Value << to_string(spec.init_from->normaliser);
    out << EndMap;
  }
  if (spec.may_diverge) out << Key << "may_diverge" << Value << true;
  out << EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace cnclab
