// Every declared field is part of a run's identity: for each
// key of each declaration, an override with another valid value must change
// the resolved config (whose hash names the result, so `reproduce` cannot
// reuse a stale result), and the resolved config must read back to itself
// (emit -> read -> emit is a fixed point). The keys come from the
// declarations, not from the emitted text, so a key that is read but not
// emitted fails here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/core/fields.hpp"
#include "cnclab/core/hash.hpp"
#include "cnclab/data/following_error.hpp"
#include "cnclab/data/friedman1.hpp"
#include "cnclab/data/ik_samples.hpp"
#include "cnclab/data/step_error.hpp"
#include "cnclab/experiment/narx_spec.hpp"
#include "cnclab/experiment/sequence_metrics.hpp"
#include "cnclab/experiment/spec.hpp"
#include "cnclab/motion/machine_fields.hpp"
#include "cnclab/train/trainer_registry.hpp"
#include "common/field_leaves.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

const std::string kBase =
    "name: t\nseed: 3\ndataset: {generator: friedman1, options: {samples: 50}}\nmodel: {}\n";

// Changes each leaf of `fields` (under `prefix`) in turn. `values` gives the
// value of keys other_value cannot choose; `skip` lists the keys left to
// other tests, each with its reason: every one must be a declared leaf.
void expect_every_key_in_identity(const std::string& base_yaml, const std::string& prefix,
                                  const std::vector<FieldInfo>& fields,
                                  std::map<std::string, std::string> values = {},
                                  std::map<std::string, std::string> skip = {},
                                  std::map<std::string, std::vector<std::string>> setup = {}) {
  std::vector<Leaf> keys;
  leaves(fields, prefix, keys);
  ASSERT_FALSE(keys.empty());
  std::set<std::string> seen;
  for (auto& leaf : keys) {
    seen.insert(leaf.key);
    if (skip.count(leaf.key)) continue;
    for (const auto& s : setup[leaf.key]) leaf.setup.push_back(s);
    const std::string value = values.count(leaf.key) ? values[leaf.key] : other_value(leaf.info);
    ASSERT_FALSE(value.empty()) << leaf.key;
    const auto base = parse_experiment(base_yaml, "e.yaml", leaf.setup);
    auto changed_overrides = leaf.setup;
    changed_overrides.push_back(leaf.key + "=" + value);
    const auto changed = parse_experiment(base_yaml, "e.yaml", changed_overrides);
    EXPECT_NE(hash_hex(changed.resolved_yaml), hash_hex(base.resolved_yaml))
        << leaf.key << "=" << value << " does not change the identity";
    EXPECT_EQ(parse_experiment(changed.resolved_yaml, "r.yaml").resolved_yaml,
              changed.resolved_yaml)
        << leaf.key;
  }
  for (const auto& [key, why] : skip) EXPECT_TRUE(seen.count(key)) << key << " (" << why << ")";
}

TEST(FieldIdentity, EveryTrainerKeyChangesTheIdentityAndRoundTrips) {
  for (const auto& trainer : trainers().all()) {
    expect_every_key_in_identity(kBase + "trainer: {type: " + trainer.name + "}\n", "trainer.",
                                 trainer.fields());
  }
}

TEST(FieldIdentity, EveryExperimentKeyChangesTheIdentityAndRoundTrips) {
  // Upstream files for needs and init_from (absolute: the test's working
  // folder is not the file's).
  testing::TempDir dir;
  std::vector<std::string> files;
  for (const char* name : {"a.yaml", "b.yaml"}) {
    const auto path = dir.path() / name;
    std::ofstream(path) << kBase << "trainer: {type: sgdm}\n";
    files.push_back(path.string());
  }
  const std::string base = kBase + "trainer: {type: sgdm}\n";
  expect_every_key_in_identity(
      base, "", experiment_fields().info(),
      {{"needs", "[" + files[0] + "]"},
       {"init_from.experiment", files[1]},
       {"dataset.targets", "[y]"},
       {"model.hidden", "[3]"},
       // below the default high (0.1)
       {"model.init.weights.low", "-1"},
       {"model.init.biases.low", "-1"}},
      {{"kind", "not emitted: only train here"},
       {"sweep", "read by `cnclab sweep`, not part of a trial's config"},
       {"slurm", "read by --slurm, not part of the identity: SlurmBlockLeavesTheIdentity"},
       {"trainer", "EveryTrainerKeyChangesTheIdentityAndRoundTrips"},
       {"dataset.generator", "another generator needs other options: GeneratorOptions"},
       {"dataset.options", "GeneratorOptions"},
       {"model.type", "narx: EveryNarxKeyChangesTheIdentityAndRoundTrips"}},
      {{"init_from.normaliser", {"init_from.experiment=" + files[0]}},
       {"split.validation_count", {"split.train_count=20"}},
       {"split.test_count", {"split.train_count=20"}}});
}

// A `slurm:` block (sweep/slurm_fields.hpp) says where a run goes, not what
// it computes: the resolved config, whose hash names the result, is the
// same with and without it.
TEST(FieldIdentity, SlurmBlockLeavesTheIdentity) {
  const std::string base = kBase + "trainer: {type: sgdm}\n";
  const auto plain = parse_experiment(base, "e.yaml");
  const auto with_block = parse_experiment(
      base + "slurm: {partition: long, time: '2-00:00:00', cpus_per_task: 8, mem: 64G}\n", "e.yaml",
      {"slurm.max_concurrent=3"});
  EXPECT_EQ(with_block.resolved_yaml, plain.resolved_yaml);
  EXPECT_EQ(hash_hex(with_block.resolved_yaml), hash_hex(plain.resolved_yaml));
}

TEST(FieldIdentity, GeneratorOptions) {
  expect_every_key_in_identity(kBase + "trainer: {type: sgdm}\n", "dataset.options.",
                               friedman1_fields().info());
}

TEST(FieldIdentity, StepErrorGeneratorOptions) {
  const std::string base =
      "name: t\nseed: 3\ndataset: {generator: step_error, options: {surface: " CNCLAB_SOURCE_DIR
      "/configs/surfaces/surface1.yaml, lines: 3, points_per_line: 4}}\nmodel: {}\n"
      "trainer: {type: sgdm}\n";
  expect_every_key_in_identity(
      base, "dataset.options.", step_error_fields().info(),
      {{"dataset.options.surface", CNCLAB_SOURCE_DIR "/configs/surfaces/surface2.yaml"},
       // (values surface 1 can still be machined with: the planner refuses others)
       {"dataset.options.tool_axis", "[0, 0, 2]"},
       {"dataset.options.max_normal_angle", "89"}});
}

TEST(FieldIdentity, FollowingErrorGeneratorOptions) {
  expect_every_key_in_identity(
      "name: t\nseed: 3\ndataset: {generator: following_error}\nmodel: {}\n"
      "trainer: {type: sgdm}\n",
      "dataset.options.", following_error_fields().info(),
      // weight_min 1.5 would exceed weight_max 1; velocity 450 would outrun the
      // planner's window overlap (stopping distance)
      {{"dataset.options.path.weight_min", "0.5"},
       {"dataset.options.limits.velocity", "200"},
       {"dataset.options.feed_factors", "[1, 0.5]"},
       {"dataset.options.extra_inputs", "[direction]"}},
      {{"dataset.options.machine", "a file name or a map: MachineKeys below"}});
}

// dataset.options.machine as a map: every key of motion/machine_fields.cpp.
TEST(FieldIdentity, FollowingErrorMachineKeys) {
  expect_every_key_in_identity(
      "name: t\nseed: 3\ndataset: {generator: following_error}\nmodel: {}\n"
      "trainer: {type: sgdm}\n",
      "dataset.options.machine.", machine_fields().info(),
      // periods that still nest (velocity loop | controller, step | velocity
      // loop); static friction >= coulomb; feedforward <= 1
      {{"dataset.options.machine.timing.velocity_loop_period", "5e-4"},
       {"dataset.options.machine.timing.integration_step", "1.25e-5"},
       {"dataset.options.machine.axes.x.coulomb_friction", "0.1"},
       {"dataset.options.machine.axes.y.coulomb_friction", "0.1"},
       {"dataset.options.machine.axes.x.velocity_feedforward", "0.5"},
       {"dataset.options.machine.axes.y.velocity_feedforward", "0.5"}});
}

TEST(FieldIdentity, IkSamplesGeneratorOptions) {
  expect_every_key_in_identity(
      "name: t\nseed: 3\ndataset: {generator: ik_samples}\nmodel: {}\ntrainer: {type: sgdm}\n",
      "dataset.options.", ik_samples_fields().info());
}

// model.type narx (narx_spec.hpp): its model keys, each key of a training
// stage and the sequence metrics. The stages list is replaced whole (an
// override cannot address one list entry).
const std::string kNarxBase =
    "name: t\nseed: 3\ndataset: {generator: friedman1, options: {samples: 50}}\n"
    "split: {mode: sequential_halves}\nnormalisation: {inputs: none, targets: none}\n"
    "model: {type: narx}\ntrainer: {stages: [{mode: open_loop, type: trainbr}]}\n";

// Sequence metrics for a narx experiment (a study registers them in the
// program; once per test process here).
const std::vector<std::string>& identity_test_sequence_metrics() {
  static const std::vector<std::string> names = [] {
    const std::vector<std::string> mine = {"identity_test_rms", "identity_test_max"};
    register_sequence_metrics(
        {"field_identity_test",
         mine,
         [](const SequencePrediction&) { return std::map<std::string, double>{}; },
         {},
         {}});
    return mine;
  }();
  return names;
}

TEST(FieldIdentity, EveryNarxKeyChangesTheIdentityAndRoundTrips) {
  identity_test_sequence_metrics();
  expect_every_key_in_identity(kNarxBase, "model.", narx_model_fields().info(),
                               {{"model.inputs", "[v, direction]"}});
}

// "trainer.stages=[{mode: open_loop, type: TYPE, KEY: VALUE}]" (no KEY: "");
// mode closed_loop for `horizon` and `fallback_horizon`, which only
// closed-loop stages have.
std::string one_stage(const std::string& type, const std::string& key, const std::string& value) {
  std::map<std::string, std::string> stage = {
      {"mode", key == "horizon" || key == "fallback_horizon" ? "closed_loop" : "open_loop"},
      {"type", type}};
  if (!key.empty()) stage[key] = value;
  std::string text;
  for (const auto& [k, v] : stage) text += (text.empty() ? "" : ", ") + k + ": " + v;
  return "trainer.stages=[{" + text + "}]";
}

TEST(FieldIdentity, EveryStageKeyChangesTheIdentityAndRoundTrips) {
  identity_test_sequence_metrics();
  for (const auto& def : trainers().all()) {
    if (!def.capabilities.needs_jacobian) continue;
    const std::string& type = def.name;
    const auto trainer = def.fields();
    std::vector<FieldInfo> keys = stage_fields().info();
    keys.insert(keys.end(), trainer.begin(), trainer.end());
    for (const auto& f : keys) {
      const auto base = parse_experiment(
          kNarxBase, "e.yaml",
          {one_stage(type, f.key == "horizon" || f.key == "fallback_horizon" ? "mode" : "",
                     "closed_loop")});
      const std::string value = other_value(f);
      ASSERT_FALSE(value.empty()) << f.key;
      const auto changed = parse_experiment(kNarxBase, "e.yaml", {one_stage(type, f.key, value)});
      EXPECT_NE(hash_hex(changed.resolved_yaml), hash_hex(base.resolved_yaml))
          << type << " stage: " << f.key << "=" << value << " does not change the identity";
      EXPECT_EQ(parse_experiment(changed.resolved_yaml, "r.yaml").resolved_yaml,
                changed.resolved_yaml)
          << f.key;
    }
  }
}

TEST(FieldIdentity, NarxMetricsAreTheSequenceMetrics) {
  const auto& names = identity_test_sequence_metrics();
  const auto all = parse_experiment(kNarxBase, "e.yaml");
  for (const auto& m : names) {
    EXPECT_NE(std::find(all.spec.metrics.begin(), all.spec.metrics.end(), m),
              all.spec.metrics.end())
        << m << " is not a default";
  }
  const auto one = parse_experiment(kNarxBase, "e.yaml", {"metrics=[" + names.front() + "]"});
  EXPECT_EQ(one.spec.metrics, std::vector<std::string>{names.front()});
  EXPECT_NE(hash_hex(one.resolved_yaml), hash_hex(all.resolved_yaml));
  EXPECT_EQ(parse_experiment(one.resolved_yaml, "r.yaml").resolved_yaml, one.resolved_yaml);
  // A regression metric is not a narx metric, nor a sequence metric an mlp one.
  EXPECT_THROW(parse_experiment(kNarxBase, "e.yaml", {"metrics=[mse]"}), ConfigError);
  EXPECT_THROW(parse_experiment(kBase + "trainer: {type: sgdm}\n", "e.yaml",
                                {"metrics=[" + names.front() + "]"}),
               ConfigError);
}

}  // namespace
}  // namespace cnclab
