#pragma once
// A sweep expanded into trials: every point (grid product or random sample)
// times every repeat, each resolved into a full experiment config whose hash
// is the trial's identity. The plan is stored as <sweep dir>/sweep.yaml so
// shards and `cnclab sweep merge` agree on the trial list.
//
// Layout of a sweep folder:
//   sweep.yaml          the plan (this file's SweepPlan), written atomically
//   trials/<id>.h5      one result file per trial (result_file.hpp)
//   trials/<id>.error   why a trial stopped without a result (exception, crash)
//   trials/.<id>.lock   while a process runs the trial: its host and pid
//                       (io/lock_file.hpp; sweep_execute.hpp, "One writer per trial")
//   summary.h5          parameters -> metrics -> status table (sweep_summary.hpp)
// A complete trial is also the result store's result of its config (hard
// link; sweep_execute.cpp, "Trials share results with the result store").
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/experiment/spec.hpp"
#include "cnclab/sweep/sweep_spec.hpp"

namespace cnclab {

struct PlannedTrial {
  std::size_t point = 0;            // index of the parameter combination
  std::size_t repeat = 0;           // 0 .. repeats-1
  std::uint64_t seed = 0;           // the trial's master seed
  std::vector<std::string> values;  // YAML text per swept key (plan order)
  std::string id;                   // hash_hex of the resolved config: 16 hex digits
  // The resolved experiment (only in the process that planned the sweep).
  std::optional<LoadedExperiment> experiment;
};

struct SweepPlan {
  std::string experiment;  // experiment name
  std::string method;      // grid | random
  std::size_t repeats = 1;
  Objective objective;
  std::vector<std::string> keys;      // swept config keys
  std::vector<std::string> metrics;   // the experiment's stored metrics (stored_metrics)
  std::vector<PlannedTrial> trials;   // points in order, repeats within a point
  std::size_t merged_duplicates = 0;  // samples whose config equalled an earlier trial's
  // Model-based methods (tpe, cmaes, nsga2, qmc; model_search.hpp) only, and
  // only then written to sweep.yaml (grid and random plans keep their text
  // and hash): the search space ("key=text" per parameter), the sampler's
  // seed, the pruner (as written in the sweep block) and report interval,
  // and every objective when there are several (the first is `objective`).
  // The trials of such a plan are the study's, in trial-number order.
  std::vector<std::string> space;
  std::uint64_t sampler_seed = 0;
  std::string pruner;
  std::string sampler;  // the sampler's options, "k=v ..." (written when any)
  std::size_t report_every = 1;
  std::vector<Objective> objectives;

  // The plan as YAML (sweep.yaml); no times or hosts: equal plans, equal text.
  std::string to_yaml() const;
  // 16 hex digits of to_yaml().
  std::string hash() const;
};

bool model_based(const SweepPlan& plan);

// The trials of one point (`values`: YAML text per key of `keys`): repeat 0
// with `seed` (the --seed option; nullopt: the experiment's), repeat r >= 1
// with derive_seed(that seed, "repeat/<r>"), each loaded (validated) and
// identified by its resolved config's hash. ConfigError naming the point.
std::vector<PlannedTrial> resolve_point(const std::filesystem::path& experiment_file,
                                        const std::vector<std::string>& overrides,
                                        std::optional<std::uint64_t> seed,
                                        const std::vector<std::string>& keys,
                                        const std::vector<YAML::Node>& values, std::size_t repeats,
                                        const std::string& profile);

// "key=value key=value": a point's swept values (keys and values in plan order).
std::string point_text(const std::vector<std::string>& keys,
                       const std::vector<std::string>& values);

// The objective a sweep ranks by. Given: its metric as named, a name without
// a split meaning its validation value ("rmse" -> validation.rmse;
// normalised_validation_mse -> validation.normalised_mse); a test.* name is
// allowed (objective_warning). Not given: the validation value of the first
// entry of the experiment's `metrics:` (`selection`), maximised for r2.
Objective resolve_objective(const std::optional<Objective>& given,
                            const std::vector<std::string>& selection);
// For people, where a sweep runs or is summarised: "" unless the objective
// is a test metric (selecting on test data), then why that misleads.
std::string objective_warning(const SweepPlan& plan);

// Expands and resolves every trial (loading each config validates it, so a
// bad key or value stops the sweep before anything runs: ConfigError).
// `overrides` are the plain overrides, `seed` the --seed option, `profile`
// the profiles: entry every trial loads with.
SweepPlan plan_sweep(const std::filesystem::path& experiment_file,
                     const std::vector<std::string>& overrides, std::optional<std::uint64_t> seed,
                     const SweepSpec& spec, const std::string& profile = {});

// The trials of shard `shard` (1-based) of `shards`: trial i (plan order)
// belongs to shard (i mod shards) + 1. Deterministic for a plan.
std::vector<std::size_t> shard_trials(std::size_t trial_count, std::size_t shard,
                                      std::size_t shards);
// Parses "K/N"; ConfigError unless 1 <= K <= N.
std::pair<std::size_t, std::size_t> parse_shard(const std::string& text);

// Writes dir/sweep.yaml, or checks that an existing one is the same plan
// (ConfigError otherwise: another sweep's folder).
void store_plan(const std::filesystem::path& dir, const SweepPlan& plan);
// Reads dir/sweep.yaml; IoError / ConfigError naming the file.
SweepPlan load_plan(const std::filesystem::path& dir);
// The same from the text of a sweep.yaml (summary.h5's /plan); `origin` names
// it in errors (IoError).
SweepPlan parse_plan(const std::string& yaml_text, const std::string& origin);

std::filesystem::path trial_result_path(const std::filesystem::path& dir, const std::string& id);
std::filesystem::path trial_error_path(const std::filesystem::path& dir, const std::string& id);
std::filesystem::path trial_lock_path(const std::filesystem::path& dir, const std::string& id);

}  // namespace cnclab
