// Sweep grammar, grid and random expansion, repeats, shards.
#include "cnclab/sweep/sweep_plan.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/train/sgdm.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

std::string config_error(const std::function<void()>& f) {
  return testing::error_message<ConfigError>(f);  // "no error" fails every find below
}

const std::string kExperiment = CNCLAB_SOURCE_DIR "/experiments/friedman/friedman1_mlp.yaml";

SweepParameter param(const std::string& key, const std::string& text) {
  auto p = parse_sweep_values(key, text);
  EXPECT_TRUE(p.has_value()) << text;
  return *p;
}

TEST(SweepGrammar, ListsSplitOnlyAtTopLevelCommas) {
  EXPECT_FALSE(parse_sweep_values("model.hidden", "[28,20]"));  // one value: plain override
  EXPECT_FALSE(parse_sweep_values("trainer.learning_rate", "1e-3"));
  const auto lists = param("model.hidden", "[28,20],[32, 16],{a: 1, b: 2}");
  ASSERT_EQ(lists.values.size(), 3u);
  EXPECT_EQ(lists.values[0].size(), 2u);
  EXPECT_EQ(lists.values[1][1].as<int>(), 16);
  EXPECT_TRUE(lists.values[2].IsMap());
  const auto quoted = param("description", "'a, b',c");
  ASSERT_EQ(quoted.values.size(), 2u);
  EXPECT_EQ(quoted.values[0].Scalar(), "a, b");
  const auto choice = param("model.hidden", "choice([8], [16,8])");
  EXPECT_EQ(choice.values.size(), 2u);
  EXPECT_TRUE(choice.enumerable());
}

TEST(SweepGrammar, RangesAndDistributions) {
  const auto r = param("trainer.epochs", "int_range(3, 11, 4)");
  const auto values = r.enumerate();
  ASSERT_EQ(values.size(), 3u);  // 3, 7, 11
  EXPECT_EQ(values[0].as<int>(), 3);
  EXPECT_EQ(values[2].as<int>(), 11);
  EXPECT_EQ(param("trainer.epochs", "int_range(1,1)").enumerate().size(), 1u);
  EXPECT_FALSE(param("x", "uniform(0, 1)").enumerable());
  EXPECT_FALSE(param("x", "log_uniform(1e-4, 1e-1)").enumerable());
}

TEST(SweepGrammar, BadValuesNameKeyAndRule) {
  const auto err = [](const std::string& text) {
    return config_error([&] { parse_sweep_values("trainer.learning_rate", text); });
  };
  EXPECT_NE(err("log_uniform(0, 1)").find("log_uniform needs 0 < low"), std::string::npos);
  EXPECT_NE(err("log_uniform(-2, -1)").find("0 < low"), std::string::npos);
  EXPECT_NE(err("uniform(1, 1)").find("low < high"), std::string::npos);
  EXPECT_NE(err("uniform(1)").find("takes (low, high)"), std::string::npos);
  EXPECT_NE(err("uniform(a, 1)").find("'a' is not a finite number"), std::string::npos);
  EXPECT_NE(err("int_range(5, 1)").find("first <= last"), std::string::npos);
  EXPECT_NE(err("int_range(1, 5, 0)").find("step must be at least 1"), std::string::npos);
  EXPECT_NE(err("choice()").find("at least one value"), std::string::npos);
  EXPECT_NE(err("1,,2").find("empty value"), std::string::npos);
  EXPECT_NE(err("normal(0, 1)").find("unknown function 'normal'"), std::string::npos);
  EXPECT_NE(config_error([] { parse_sweep_values("bad key", "1,2"); }).find("invalid character"),
            std::string::npos);
  EXPECT_NE(config_error([] { parse_shard("3/2"); }).find("K must be between 1 and N"),
            std::string::npos);
  EXPECT_NE(config_error([] { parse_shard("1/0"); }).find("between 1 and N"), std::string::npos);
  EXPECT_NE(config_error([] { parse_shard("x"); }).find("expected K/N"), std::string::npos);
  EXPECT_NE(config_error([] { parse_objective("rmse:median"); }).find("METRIC:max"),
            std::string::npos);
}

SweepSpec spec_of(std::initializer_list<std::pair<std::string, std::string>> params) {
  SweepSpec s;
  for (const auto& [k, v] : params) s.set(param(k, v));
  return s;
}

const std::vector<std::string> kFast = {"trainer.epochs=2", "dataset.options.samples=50"};

// Linked keys (k1+k2): one parameter, each value set on every key; a plain
// value on the command line is an override of each key.
TEST(SweepPlan, LinkedKeysSetEveryKeyToTheSameValue) {
  const SweepSpec s = spec_of({{"trainer.learning_rate+trainer.momentum", "0.1,0.2,0.3"}});
  const SweepPlan plan = plan_sweep(kExperiment, kFast, std::nullopt, s);
  ASSERT_EQ(plan.trials.size(), 3u);  // a grid of 3 points, not 9
  EXPECT_EQ(plan.keys, std::vector<std::string>{"trainer.learning_rate+trainer.momentum"});
  for (const auto& t : plan.trials) {
    const auto& sgdm = trainer_options<SgdmOptions>(t.experiment->spec.trainer);
    EXPECT_EQ(sgdm.learning_rate, std::stod(t.values[0]));
    EXPECT_EQ(sgdm.momentum, std::stod(t.values[0]));
  }
  EXPECT_EQ(linked_keys("a.b+c.d+e"), (std::vector<std::string>{"a.b", "c.d", "e"}));
  const SweepArguments one = split_sweep_arguments({"trainer.learning_rate+trainer.momentum=0.5"});
  EXPECT_TRUE(one.parameters.empty());
  EXPECT_EQ(one.overrides,
            (std::vector<std::string>{"trainer.learning_rate=0.5", "trainer.momentum=0.5"}));
  EXPECT_NE(
      config_error([&] { parse_sweep_values("trainer.learning_rate+", "1,2"); }).find("empty"),
      std::string::npos);
}

TEST(SweepPlan, GridIsTheCartesianProductTimesRepeats) {
  SweepSpec s = spec_of(
      {{"model.dropout.keep_probability", "0.5,0.75,1.0"}, {"trainer.learning_rate", "1e-3,1e-2"}});
  s.repeats = 2;
  const SweepPlan plan = plan_sweep(kExperiment, kFast, std::nullopt, s);
  EXPECT_EQ(plan.method, "grid");
  ASSERT_EQ(plan.trials.size(), 12u);
  std::set<std::vector<std::string>> combos;
  std::set<std::string> ids;
  for (const auto& t : plan.trials) {
    combos.insert(t.values);
    ids.insert(t.id);
    EXPECT_EQ(t.id, hash_hex(t.experiment->resolved_yaml));
    EXPECT_EQ(t.point, static_cast<std::size_t>(&t - plan.trials.data()) / 2);
  }
  EXPECT_EQ(ids.size(), 12u);  // every trial its own config
  std::set<std::vector<std::string>> expected;
  for (const char* p : {"0.5", "0.75", "1.0"}) {
    for (const char* lr : {"1e-3", "1e-2"}) expected.insert({p, lr});
  }
  EXPECT_EQ(combos, expected);
  // First parameter varies slowest; repeats are adjacent within a point.
  EXPECT_EQ(plan.trials[0].values, (std::vector<std::string>{"0.5", "1e-3"}));
  EXPECT_EQ(plan.trials[1].values, plan.trials[0].values);
  EXPECT_EQ(plan.trials[2].values, (std::vector<std::string>{"0.5", "1e-2"}));
  EXPECT_EQ(plan.trials[11].point, 5u);
  // Trial 0 is exactly the plain run of its overrides (same identity).
  std::vector<std::string> overrides = kFast;
  overrides.push_back("model.dropout.keep_probability=0.5");
  overrides.push_back("trainer.learning_rate=1e-3");
  EXPECT_EQ(plan.trials[0].id, hash_hex(load_experiment(kExperiment, overrides).resolved_yaml));
  // Repeat 0 keeps the experiment seed; other repeats have other seeds, the
  // same for every point (common random numbers across points).
  EXPECT_EQ(plan.trials[0].seed, 42u);
  EXPECT_NE(plan.trials[1].seed, 42u);
  EXPECT_EQ(plan.trials[1].seed, plan.trials[3].seed);
}

TEST(SweepPlan, RandomSearchIsDeterministicForASeedAndWithinBounds) {
  SweepSpec s = spec_of({{"trainer.learning_rate", "log_uniform(1e-4, 1e-1)"},
                         {"model.dropout.keep_probability", "uniform(0.5, 1.0)"},
                         {"trainer.batch_size", "int_range(8, 64, 8)"},
                         {"model.hidden_activation", "choice(relu, tanh)"}});
  s.trials = 40;
  const SweepPlan a = plan_sweep(kExperiment, kFast, std::nullopt, s);
  const SweepPlan b = plan_sweep(kExperiment, kFast, std::nullopt, s);
  EXPECT_EQ(a.method, "random");
  EXPECT_EQ(a.to_yaml(), b.to_yaml());
  ASSERT_EQ(a.trials.size(), 40u);
  std::size_t below_geometric_mid = 0;
  std::set<std::string> activations;
  for (const auto& t : a.trials) {
    const double lr = std::stod(t.values[0]);
    EXPECT_GE(lr, 1e-4);
    EXPECT_LT(lr, 1e-1);
    if (lr < std::sqrt(1e-4 * 1e-1)) ++below_geometric_mid;
    const double keep = std::stod(t.values[1]);
    EXPECT_GE(keep, 0.5);
    EXPECT_LT(keep, 1.0);
    const int batch = std::stoi(t.values[2]);
    EXPECT_EQ(batch % 8, 0);
    EXPECT_GE(batch, 8);
    EXPECT_LE(batch, 64);
    activations.insert(t.values[3]);
    // The sampled value is the one in the trial's config.
    EXPECT_DOUBLE_EQ(trainer_options<SgdmOptions>(t.experiment->spec.trainer).learning_rate, lr);
  }
  EXPECT_EQ(activations, (std::set<std::string>{"relu", "tanh"}));
  // log-uniform: half the mass below the geometric midpoint (binomial(40, .5):
  // 10..30 holds with probability > 0.998).
  EXPECT_GE(below_geometric_mid, 10u);
  EXPECT_LE(below_geometric_mid, 30u);

  // Another sampling seed, other points; more trials keep the first ones.
  SweepSpec other = s;
  other.seed = 7;
  EXPECT_NE(plan_sweep(kExperiment, kFast, std::nullopt, other).trials[0].values,
            a.trials[0].values);
  SweepSpec more = s;
  more.trials = 50;
  const SweepPlan m = plan_sweep(kExperiment, kFast, std::nullopt, more);
  for (std::size_t i = 0; i < a.trials.size(); ++i) EXPECT_EQ(m.trials[i].id, a.trials[i].id);
}

TEST(SweepPlan, IdenticalSamplesAreOneTrial) {
  SweepSpec s = spec_of({{"trainer.learning_rate", "choice(0.01)"}});
  s.method = SweepMethod::random;
  s.trials = 5;
  const SweepPlan plan = plan_sweep(kExperiment, kFast, std::nullopt, s);
  EXPECT_EQ(plan.trials.size(), 1u);
  EXPECT_EQ(plan.merged_duplicates, 4u);
}

TEST(SweepPlan, BadSpecsAreConfigErrors) {
  SweepSpec unknown = spec_of({{"trainer.momentm", "0.1,0.2"}});
  EXPECT_NE(config_error([&] {
              plan_sweep(kExperiment, kFast, std::nullopt, unknown);
            }).find("trainer.momentm: unknown key"),
            std::string::npos);
  SweepSpec grid = spec_of({{"trainer.learning_rate", "uniform(0.1, 0.2)"}});
  grid.method = SweepMethod::grid;
  EXPECT_NE(config_error([&] { grid.validate(); }).find("cannot enumerate"), std::string::npos);
  SweepSpec random = spec_of({{"trainer.learning_rate", "uniform(0.1, 0.2)"}});
  EXPECT_NE(config_error([&] { random.validate(); }).find("needs a number of trials"),
            std::string::npos);
  EXPECT_NE(config_error([] { SweepSpec{}.validate(); }).find("no parameters"), std::string::npos);
  SweepSpec objective = spec_of({{"trainer.learning_rate", "0.1,0.2"}});
  objective.objective = Objective{"accuracy", true};
  EXPECT_NE(config_error([&] {
              plan_sweep(kExperiment, kFast, std::nullopt, objective);
            }).find("'validation.accuracy' is not among"),
            std::string::npos);
}

TEST(SweepPlan, ShardsPartitionTheTrials) {
  for (std::size_t n : {1u, 2u, 3u, 7u}) {
    std::multiset<std::size_t> all;
    for (std::size_t k = 1; k <= n; ++k) {
      const auto mine = shard_trials(10, k, n);
      EXPECT_LE(mine.size(), (10 + n - 1) / n);
      all.insert(mine.begin(), mine.end());
    }
    std::multiset<std::size_t> expected;
    for (std::size_t i = 0; i < 10; ++i) expected.insert(i);
    EXPECT_EQ(all, expected) << n;
  }
}

TEST(SweepPlan, StoredPlanReadsBackAndGuardsItsFolder) {
  TempDir dir;
  SweepSpec s = spec_of({{"trainer.learning_rate", "1e-3,1e-2"}});
  s.repeats = 2;
  const SweepPlan plan = plan_sweep(kExperiment, kFast, std::nullopt, s);
  store_plan(dir.path(), plan);
  store_plan(dir.path(), plan);  // the same plan again (another shard): fine
  const SweepPlan back = load_plan(dir.path());
  EXPECT_EQ(back.to_yaml(), plan.to_yaml());
  SweepSpec other = spec_of({{"trainer.learning_rate", "1e-4,1e-2"}});
  const SweepPlan different = plan_sweep(kExperiment, kFast, std::nullopt, other);
  EXPECT_NE(config_error([&] { store_plan(dir.path(), different); }).find("holds another sweep"),
            std::string::npos);
}

}  // namespace
}  // namespace cnclab
