#include "cnclab/experiment/spec.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <filesystem>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/core/suggest.hpp"
#include "cnclab/experiment/model_spec.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/experiment/spec_narx.hpp"
#include "cnclab/experiment/spec_text.hpp"
#include "cnclab/nn/metrics.hpp"

namespace cnclab {
namespace {

// The rule of `name`: a file-name-safe identifier (results/<name>/).
Rule name_rule() {
  return Rule::matches("^[A-Za-z0-9_-][A-Za-z0-9_.-]*$",
                       "must be a file-name-safe identifier (letters, digits, '_', '-', '.')");
}

const std::vector<std::pair<std::string, Scaling>> kScalings = {
    {"zscore", Scaling::zscore}, {"minmax", Scaling::minmax}, {"none", Scaling::none}};

const FieldList<NormalisationSpec>& normalisation_fields() {
  using N = NormalisationSpec;
  static const auto fields =
      FieldList<N>()
          .choice("inputs", &N::inputs, kScalings,
                  "zscore (seed 000 Eq. 7, n-1 std), minmax (MATLAB mapminmax) or none; fitted "
                  "on the training split")
          .choice("targets", &N::targets, kScalings, "as inputs, for the targets")
          .field("input_range", &N::input_range,
                 "[low, high] of minmax inputs (a sigmoid output needs one inside (0, 1))")
          .when("inputs", {"minmax"}, "applies to minmax only")
          .field("target_range", &N::target_range, "[low, high] of minmax targets")
          .when("targets", {"minmax"}, "applies to minmax only");
  return fields;
}

const FieldList<InitFromSpec>& init_from_fields() {
  using I = InitFromSpec;
  static const auto fields =
      FieldList<I>()
          .field("experiment", &I::experiment,
                 "experiment file (relative to this file) whose trained network parameters are "
                 "the starting point (fine-tuning)")
          .required()
          .choice("normaliser", &I::normaliser,
                  {{"refit", NormaliserSource::refit}, {"keep", NormaliserSource::keep}},
                  "refit: fit the normaliser on this experiment's training split; keep: the "
                  "upstream result's, unchanged");
  return fields;
}

// model: model.type picks the declaration (model_types()); the key tables
// show mlp's keys, the schema every type's.
FieldInfo model_info() {
  FieldInfo i = custom_info("model", "the network; model.type (mlp or narx) picks its keys",
                            FieldKind::section);
  i.children = mlp_fields().info();
  return i;
}

// Read after split and normalisation, which a narx model checks.
void read_model_section(const ConfigReader& root, ExperimentSpec& spec) {
  if (read_model_type(root.section("model")) == "narx") {
    read_narx_model_section(root, spec);
  } else {
    mlp_fields().read(root.section("model"), spec.model);
  }
}

// trainer.type and its options, or trainer.stages for model.type narx.
void read_trainer_section(const ConfigReader& root, ExperimentSpec& spec) {
  if (spec.narx) {
    read_narx_trainer(root, spec);
  } else {
    spec.trainer = read_trainer(root.section("trainer"), &spec.reader_notes);
  }
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

void check_train_kind(const ConfigReader& root) {
  if (root.get<std::string>("kind", "train") != "train") {
    root.fail("kind",
              "must be train here (other kinds are read by their job, experiment/job_kinds.hpp)");
  }
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
    root.section("trainer").fail("type", "is required (" + join(trainer_names(), ", ") + ")" +
                                             fragment_hint(base, "trainers"));
  }
}

// Checks the split against the sample count; SplitOptions names its fields
// *_fraction, the YAML keys are shorter.
void validate_split(const ConfigReader& r, const SplitOptions& s, std::size_t samples) {
  r.validate([&] {
    try {
      s.validate_for(samples);
    } catch (const OptionError& e) {
      const std::string key = e.field() == "train_fraction"        ? "train"
                              : e.field() == "validation_fraction" ? "validation"
                                                                   : e.field();
      throw OptionError(key, e.value(), e.rule());
    }
  });
}

// The keys the declarations cannot check alone: file references, rules
// across sections, metric names.
void check_experiment(const ConfigReader& root, const std::filesystem::path& base,
                      ExperimentSpec& spec) {
  if (spec.split.mode == SplitMode::random) {
    validate_split(root.section("split"), spec.split, spec.dataset.generator->shape().samples);
  }
  if (!spec.narx) validate_mlp_model(root.section("model"), spec.model);
  if (!trainer_capabilities(spec.trainer).dropout && spec.model.dropout_keep_probability < 1.0) {
    root.section("model").section("dropout").fail(
        "keep_probability", "must be 1 with trainer " + trainer_name(spec.trainer) +
                                " (it trains a deterministic network, without dropout)");
  }
  const auto known = spec.narx ? metric_selection_names(sequence_metric_names(), {"validation"})
                               : metric_selection_names(base_metrics(), metric_splits());
  for (const auto& m : spec.metrics) {
    if (std::find(known.begin(), known.end(), m) == known.end()) {
      const bool test_of_narx = spec.narx && metric_split(m) == "test";
      root.fail("metrics", "unknown metric '" + m + "'" +
                               (test_of_narx ? " (model.type narx has no test split: its metrics "
                                               "are of the validation half)"
                                             : did_you_mean(m, known)) +
                               "; " + one_of(known));
    }
  }
  for (const auto& text : spec.needs) {
    spec.needs_files.push_back(upstream_file(root, "needs", text, base));
  }
  if (spec.init_from) {
    spec.init_from->resolved_file =
        upstream_file(root.section("init_from"), "experiment", spec.init_from->experiment, base);
  }
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
  // the command line (as Hydra's defaults list): `trainer=NAME
  // trainer.epochs=5` and `trainer.epochs=5 trainer=NAME` both train 5.
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
  // The first errors a user meets: the kind, the name, what is learnt.
  check_train_kind(root);
  read_experiment_name(root);
  root.require<std::uint64_t>("seed");  // read again by the declarations
  require_subject(root, base);
  experiment_fields().read(root, spec);
  check_experiment(root, base, spec);
  check_training_samples(root, spec);
  doc.check_all_consumed();
  return {spec, to_yaml(spec), spec.reader_notes};
}

std::vector<Override> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<Override> out;
  for (const auto& text : texts) out.push_back(parse_override(text));
  return out;
}

}  // namespace

const FieldList<ExperimentSpec>& experiment_fields() {
  using E = ExperimentSpec;
  const auto never = [](const E&) { return false; };
  const auto nothing = [](const E&) { return YAML::Node(); };
  static const auto fields =
      FieldList<E>()
          .custom(
              custom_info("kind", "train (this file trains a network) or a job kind",
                          FieldKind::string, Rule::one_of({"train"})),
              [](const ConfigReader& r, E&) { check_train_kind(r); }, nothing, never)
          .field("name", &E::name, "result folder and file name (results/<name>/)", name_rule())
          .required()
          .field("description", &E::description, "free text, stored in the result")
          .field("seed", &E::seed,
                 "master seed; the split, initial weights, dropout masks, shuffling and the "
                 "generator each draw from their own stream derived from it by name")
          .required()
          .section("dataset", &E::dataset, dataset_fields(), "what data the experiment learns")
          .section("split", &E::split, split_fields(),
                   "train / validation / test split; the rest after train and validation is "
                   "the test set")
          .section("normalisation", &E::normalisation, normalisation_fields(),
                   "input and target scaling, fitted on the training split")
          .custom(model_info(), read_model_section,
                  [](const E& s) {
                    return s.narx ? narx_model_to_node(*s.narx) : mlp_fields().to_node(s.model);
                  })
          .custom(custom_info("trainer",
                              "the training algorithm (trainer.type) and its options; "
                              "model.type narx: trainer.stages instead"),
                  read_trainer_section,
                  [](const E& s) {
                    return s.narx ? stages_to_node(s.stages) : trainer_to_node(s.trainer);
                  })
          .field("metrics", &E::metrics,
                 "metrics to store: a name (mse, rmse, mae, max_abs_error, r2 in physical "
                 "units; normalised_mse in the scaled units) means it on the train, validation "
                 "and test splits (train.rmse, validation.rmse, test.rmse); "
                 "<split>.<name> only that one (metrics.hpp); model.type narx: the registered "
                 "sequence metrics (sequence_metrics.hpp), on the validation half only, all "
                 "of them by default",
                 Rule::one_of(metric_selection_names(base_metrics(), metric_splits())))
          .field("needs", &E::needs,
                 "experiment files (relative to this file) whose results this one depends on")
          .omit_default()
          .optional_section("init_from", &E::init_from, init_from_fields(),
                            "start from another experiment's trained network (fine-tuning)")
          .field("may_diverge", &E::may_diverge,
                 "true: a diverged training is this experiment's expected outcome (exit 0, "
                 "result status failed with the reason)")
          .omit_default()
          .custom(
              custom_info("sweep",
                          "the sweep block, read only by `cnclab sweep` (README: "
                          "Sweeps)"),
              [](const ConfigReader& r, E&) { r.raw("sweep"); }, nothing, never)
          .custom(
              custom_info("slurm",
                          "defaults of `--slurm`'s options, read only by `sweep --slurm` and "
                          "`reproduce --slurm`; never part of the result's identity (README: "
                          "Slurm)"),
              [](const ConfigReader& r, E&) { r.raw("slurm"); }, nothing, never);
  return fields;
}

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
  const Rule rule = name_rule();
  if (!rule.holds(name)) root.fail("name", rule.text(false));
  return name;
}

std::vector<std::string> metric_splits_of(const ExperimentSpec& spec) {
  if (spec.narx) return {"validation"};
  const SplitOptions::Sizes sizes = spec.split.sizes(spec.dataset.generator->shape().samples);
  std::vector<std::string> splits;
  if (sizes.train > 0) splits.emplace_back("train");
  if (sizes.validation > 0) splits.emplace_back("validation");
  if (sizes.test > 0) splits.emplace_back("test");
  return splits;
}

std::vector<std::string> stored_metrics(const ExperimentSpec& spec) {
  // Entries naming a split without samples ("validation.rmse" with no
  // validation split) are accepted and store nothing: a shared metrics list
  // fits every split of its experiments.
  const std::vector<std::string> splits = metric_splits_of(spec);
  std::vector<std::string> selection;
  for (const auto& m : spec.metrics) {
    const std::string split = m == kOlderValidationMse ? "validation" : metric_split(m);
    if (split.empty() || std::find(splits.begin(), splits.end(), split) != splits.end()) {
      selection.push_back(m);
    }
  }
  if (spec.narx) return expand_metric_selection(selection, sequence_metric_names(), splits);
  return expand_metric_selection(selection, base_metrics(), splits);
}

LoadedExperiment load_experiment(const std::filesystem::path& file,
                                 const std::vector<Override>& overrides,
                                 std::optional<std::uint64_t> seed_override,
                                 const std::string& profile) {
  ConfigDocument doc = ConfigDocument::load(file, profile);
  LoadedExperiment loaded = read_experiment(doc, overrides, seed_override, file.parent_path());
  loaded.spec.source_file = file;
  loaded.spec.profile = profile;
  for (const auto& o : overrides) loaded.spec.overrides.push_back(o.text);
  if (seed_override) loaded.spec.overrides.push_back("seed=" + std::to_string(*seed_override));
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
  return experiment_fields().yaml(spec);
}

}  // namespace cnclab
