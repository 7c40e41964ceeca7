#include "cnclab/experiment/spec.hpp"

#include <gtest/gtest.h>

#include "cnclab/core/error.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/sgdm.hpp"
#include "cnclab/train/trainbr.hpp"

namespace cnclab {
namespace {

// What every experiment must name (no silent default dataset,
// model or trainer), and the rest of a minimal experiment.
const std::string kHead = "name: t\nseed: 3\n";
const std::string kDataset = "dataset: {generator: friedman1}\n";
const std::string kModel = "model: {type: mlp}\n";
const std::string kTrainer = "trainer: {type: sgdm}\n";
const std::string kNoTrainer = kHead + kDataset + kModel;
const std::string kMinimal = kNoTrainer + kTrainer;

std::string error_of(const std::string& yaml, const std::vector<std::string>& overrides = {}) {
  try {
    parse_experiment(yaml, "e.yaml", overrides);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Spec, DefaultsApplyAndResolvedYamlReloadsToTheSameSpec) {
  const auto a = parse_experiment(kMinimal, "e.yaml");
  EXPECT_EQ(a.spec.name, "t");
  EXPECT_EQ(a.spec.seed, 3u);
  EXPECT_DOUBLE_EQ(trainer_options<SgdmOptions>(a.spec.trainer).momentum, SgdmOptions{}.momentum);
  // Round trip: the resolved text is itself a valid experiment with no
  // unknown keys, and resolves to the identical text.
  const auto b = parse_experiment(a.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(a.resolved_yaml, b.resolved_yaml);
}

TEST(Spec, OverridesAreTypedAsYaml) {
  const auto a = parse_experiment(kMinimal, "e.yaml",
                                  {"model.hidden=[28, 20]", "trainer.learning_rate=1e-4",
                                   "trainer.shuffle=false", "model.dropout.keep_probability=0.5"});
  EXPECT_EQ(a.spec.model.hidden, (std::vector<std::size_t>{28, 20}));
  EXPECT_DOUBLE_EQ(trainer_options<SgdmOptions>(a.spec.trainer).learning_rate, 1e-4);
  EXPECT_FALSE(trainer_options<SgdmOptions>(a.spec.trainer).shuffle);
  EXPECT_DOUBLE_EQ(a.spec.model.dropout_keep_probability, 0.5);
}

TEST(Spec, RequiredKeysAndUnknownKeys) {
  EXPECT_NE(error_of("seed: 1\n").find("name"), std::string::npos);
  EXPECT_NE(error_of("name: x\n").find("seed"), std::string::npos);
  EXPECT_NE(error_of(kMinimal + "trainr: {}\n").find("e.yaml:6:1: trainr: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + kModel + kTrainer +
                     "dataset:\n  generator: friedman1\n  options:\n    sample: 10\n")
                .find("dataset.options.sample: unknown key (did you mean 'samples'?)"),
            std::string::npos);
}

// An experiment that forgets its dataset include must not
// train on a built-in data set; model and trainer type are required too.
TEST(Spec, DatasetGeneratorModelAndTrainerTypeAreRequired) {
  EXPECT_NE(error_of(kHead + kModel + kTrainer).find("dataset.generator: is required"),
            std::string::npos)
      << error_of(kHead + kModel + kTrainer);
  EXPECT_NE(error_of(kHead + kModel + kTrainer + "dataset: {options: {samples: 10}}\n")
                .find("dataset.generator: is required"),
            std::string::npos);
  EXPECT_NE(error_of(kHead + kDataset + kTrainer).find("model: is required"), std::string::npos);
  EXPECT_NE(error_of(kNoTrainer).find("trainer.type: is required (sgdm, lm, trainbr"),
            std::string::npos);
  EXPECT_NE(error_of(kNoTrainer + "trainer: {epochs: 3}\n").find("trainer.type: is required"),
            std::string::npos);
}

// Every enumerated value gets "did you mean".
TEST(Spec, MisspeltEnumeratedValuesGetDidYouMean) {
  EXPECT_NE(error_of(kMinimal, {"metrics=[mse,rsme]"})
                .find("unknown metric 'rsme' (did you mean 'rmse'?)"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"model.hidden_activation=tahn"}).find("(did you mean 'tanh'?)"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"trainer.type=trainbrr"}).find("(did you mean 'trainbr'?)"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"normalisation.inputs=minmx"}).find("(did you mean 'minmax'?)"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"dataset.generator=friedman"}).find("(did you mean 'friedman1'?)"),
            std::string::npos);
  // Far from every name: no guess.
  EXPECT_EQ(error_of(kMinimal, {"trainer.type=adam"}).find("did you mean"), std::string::npos);
}

TEST(Spec, OutOfRangeValuesNameKeyValueAndLocation) {
  EXPECT_NE(error_of(kNoTrainer + "trainer:\n  type: sgdm\n  momentum: 1.5\n")
                .find("e.yaml:7:13: trainer.momentum = 1.5"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"split.train=1.2"}).find("split.train = 1.2"), std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"model.dropout.keep_probability=0"})
                .find("model.dropout.keep_probability = 0"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"model.hidden_activation=swish"}).find("must be one of"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"metrics=[mse, accuracy]"}).find("unknown metric 'accuracy'"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"dataset.options.inputs=3"}).find("dataset.options.inputs = 3"),
            std::string::npos);
  EXPECT_NE(error_of("name: ../evil\nseed: 1\n").find("file-name-safe"), std::string::npos);
}

TEST(Spec, InitializerKeysDependOnType) {
  const auto a =
      parse_experiment(kMinimal, "e.yaml", {"model.init.weights={type: normal, mean: 0, std: 2}"});
  EXPECT_DOUBLE_EQ(a.spec.model.weights.std, 2.0);
  // `std` belongs to normal only: with xavier it is an unknown key.
  EXPECT_NE(error_of(kMinimal, {"model.init.weights={type: xavier, std: 2}"}).find("unknown key"),
            std::string::npos);
}

TEST(Spec, GraphKeysAndSweepBlock) {
  // Upstream files must exist; the message names the key.
  EXPECT_NE(error_of(kMinimal + "needs: [nowhere.yaml]\n")
                .find("needs = [nowhere.yaml]: no experiment file"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal + "init_from: {experiment: nowhere.yaml}\n")
                .find("init_from.experiment = nowhere.yaml: no experiment file"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal + "init_from: {experimnt: a.yaml}\n")
                .find("init_from.experiment: is required"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal + "needs: other.yaml\n").find("expected a list"), std::string::npos);
  // The sweep block belongs to `cnclab sweep`: not part of a run's config.
  const auto with_sweep =
      parse_experiment(kMinimal + "sweep: {repeats: 3, parameters: {seed: [1, 2]}}\n", "e.yaml");
  EXPECT_EQ(with_sweep.resolved_yaml, parse_experiment(kMinimal, "e.yaml").resolved_yaml);
  EXPECT_EQ(with_sweep.resolved_yaml.find("sweep"), std::string::npos);
}

TEST(Spec, LevenbergMarquardtTrainersWithMatlabDefaults) {
  const auto lm = parse_experiment(kNoTrainer + "trainer: {type: lm}\n", "e.yaml");
  const auto& l = trainer_options<LmOptions>(lm.spec.trainer);
  EXPECT_EQ(l.mu, 1e-3);  // trainlm
  EXPECT_EQ(l.epochs, 1000u);
  EXPECT_NE(lm.resolved_yaml.find("type: lm\n  epochs: 1000\n  goal: 0\n  mu: 0.001\n"
                                  "  mu_dec: 0.1\n  mu_inc: 10\n  mu_max: 10000000000\n"
                                  "  min_gradient: 1e-07"),
            std::string::npos)
      << lm.resolved_yaml;
  const auto br =
      parse_experiment(kNoTrainer + "trainer: {type: trainbr, mu_max: 1e8}\n", "e.yaml");
  const auto& b = trainer_options<TrainbrOptions>(br.spec.trainer);
  EXPECT_EQ(b.mu, 5e-3);  // trainbr
  EXPECT_EQ(b.mu_max, 1e8);
  // Resolved text reloads to the same spec, for both.
  EXPECT_EQ(parse_experiment(lm.resolved_yaml, "r.yaml").resolved_yaml, lm.resolved_yaml);
  EXPECT_EQ(parse_experiment(br.resolved_yaml, "r.yaml").resolved_yaml, br.resolved_yaml);
  // Overridable from the command line like any key.
  const auto o = parse_experiment(kMinimal, "e.yaml", {"trainer={type: trainbr, epochs: 7}"});
  EXPECT_EQ(trainer_options<TrainbrOptions>(o.spec.trainer).epochs, 7u);
}

// Switching trainer.type drops the keys only the old trainer
// has (one note names them) and keeps the shared ones; a key of no trainer is
// still an unknown key.
TEST(Spec, SwitchingTrainerTypeDropsTheOldTrainersKeysWithANote) {
  const std::string sgdm =
      kNoTrainer + "trainer: {type: sgdm, learning_rate: 0.01, momentum: 0.9, epochs: 7}\n";
  const auto a = parse_experiment(sgdm, "e.yaml", {"trainer.type=trainbr"});
  ASSERT_TRUE(trainer_options_if<TrainbrOptions>(a.spec.trainer) != nullptr);
  EXPECT_EQ(trainer_options<TrainbrOptions>(a.spec.trainer).epochs, 7u);  // shared key kept
  ASSERT_EQ(a.notes.size(), 1u);
  EXPECT_EQ(a.notes[0],
            "trainer.type is trainbr: dropped learning_rate, momentum (keys of another trainer)");
  EXPECT_EQ(a.resolved_yaml.find("learning_rate"), std::string::npos);
  EXPECT_TRUE(parse_experiment(sgdm, "e.yaml").notes.empty());
  // Written together with the type they do not belong to: still unknown keys
  // (a mistake, not a switch).
  EXPECT_NE(error_of(kNoTrainer + "trainer: {type: lm, learning_rate: 0.01}\n")
                .find("trainer.learning_rate: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(sgdm, {"trainer.type=trainbr", "trainer.momentm=1"})
                .find("trainer.momentm: unknown key"),
            std::string::npos);
}

TEST(Spec, TrainerErrorsNameKeyValueAndRule) {
  // The registered trainers, the built-in ones first.
  EXPECT_NE(error_of(kNoTrainer + "trainer:\n  type: rprop\n")
                .find("e.yaml:6:9: trainer.type = rprop: must be one of: sgdm, lm, trainbr"),
            std::string::npos)
      << error_of(kNoTrainer + "trainer:\n  type: rprop\n");
  EXPECT_NE(error_of(kMinimal, {"trainer={type: lm, mu: -1}"})
                .find("trainer.mu = -1: must be a finite number > 0"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"trainer={type: trainbr, mu_inc: 0.5}"})
                .find("trainer.mu_inc = 0.5: must be a finite number > 1"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"trainer={type: lm, mu: 1e12}"})
                .find("trainer.mu = 1e12: must not exceed mu_max = 1e+10"),
            std::string::npos)
      << error_of(kMinimal, {"trainer={type: lm, mu: 1e12}"});
  // Keys of another trainer type are unknown keys.
  EXPECT_NE(error_of(kMinimal, {"trainer={type: lm, learning_rate: 0.1}"})
                .find("trainer.learning_rate: unknown key"),
            std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"trainer={type: sgdm, mu: 0.1}"}).find("trainer.mu: unknown key"),
            std::string::npos);
  // Dropout makes the objective random: not with Levenberg-Marquardt.
  EXPECT_NE(error_of(kMinimal, {"trainer={type: trainbr}", "model.dropout.keep_probability=0.5"})
                .find("model.dropout.keep_probability = 0.5: must be 1 with trainer trainbr"),
            std::string::npos);
}

TEST(Spec, NormalisationMinMax) {
  const auto a =
      parse_experiment(kMinimal + "normalisation: {inputs: minmax, targets: none}\n", "e.yaml");
  EXPECT_EQ(a.spec.normalisation.inputs, Scaling::minmax);
  EXPECT_EQ(a.spec.normalisation.targets, Scaling::none);
  EXPECT_NE(a.resolved_yaml.find("inputs: minmax"), std::string::npos);
  EXPECT_NE(error_of(kMinimal, {"normalisation.inputs=mapminmax"})
                .find("normalisation.inputs = mapminmax: must be one of: zscore, minmax, none"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab

namespace cnclab {
namespace {

const std::string kIk = kHead + kModel + kTrainer + "dataset:\n  generator: ik_samples\n";

TEST(SpecIk, TargetsCountsAndMinmaxReadAndRoundTrip) {
  const auto a = parse_experiment(kIk +
                                      "  targets: [X]\nsplit:\n  train_count: 1042\n"
                                      "  test_count: 1040\nnormalisation:\n  targets: minmax\n"
                                      "  target_range: [0.1, 0.9]\n",
                                  "e.yaml");
  EXPECT_EQ(a.spec.dataset.targets, std::vector<std::string>{"X"});
  EXPECT_EQ(a.spec.split.train_count, 1042u);
  EXPECT_EQ(a.spec.split.test_count, 1040u);
  EXPECT_FALSE(a.spec.split.validation_count.has_value());
  EXPECT_EQ(a.spec.normalisation.targets, Scaling::minmax);
  EXPECT_EQ(a.spec.normalisation.target_range[0], 0.1);
  const auto b = parse_experiment(a.resolved_yaml, "resolved.yaml");
  EXPECT_EQ(a.resolved_yaml, b.resolved_yaml);
}

TEST(SpecIk, SplitAndRangeMistakesAreErrors) {
  // Table 5's counts do not add up to the 3125 samples of the grid.
  EXPECT_NE(error_of(kIk, {"split.train_count=1042", "split.validation_count=348",
                           "split.test_count=1042"})
                .find("split.test_count = 1042"),
            std::string::npos);
  EXPECT_NE(error_of(kIk, {"split.train_count=1042", "split.train=0.5"}).find("either fractions"),
            std::string::npos);
  EXPECT_NE(error_of(kIk, {"split.test_count=10"}).find("needs train_count"), std::string::npos);
  EXPECT_NE(error_of(kIk, {"normalisation.targets=minmax", "normalisation.target_range=[1, 0]"})
                .find("low < high"),
            std::string::npos);
  EXPECT_NE(error_of(kIk, {"normalisation.target_range=[0, 1]"}).find("applies to minmax only"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab
