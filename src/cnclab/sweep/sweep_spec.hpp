#pragma once
// What a sweep varies and how: the `sweep:` block of an experiment file and
// the same on the command line. Grammar of a parameter's values (the text
// after `key=` on the command line, or a YAML string in the block):
//
//   v1,v2,...            a list: every value in a grid, one of them at random
//   choice(v1,v2,...)    the same, written as a function
//   int_range(lo,hi)     integers lo..hi inclusive; int_range(lo,hi,step)
//   uniform(lo,hi)       a real number drawn uniformly from [lo, hi)   (not in a grid)
//   log_uniform(lo,hi)   exp(uniform(ln lo, ln hi)), 0 < lo < hi      (not in a grid)
//
// The model-based methods (tpe, cmaes, nsga2, qmc: Optuna's samplers,
// model_search.hpp) take the same grammar: a list or choice() is Optuna's
// categorical, int_range its int (with step), uniform and log_uniform its
// float (log = true).
//
// Each value is YAML (as for overrides): 1e-4 is a number, [28,20] a list.
// Commas inside [...], {...}, (...) or quotes do not separate values, so
// `model.hidden=[28,20],[32,16]` is two values and `model.hidden=[28,20]` one
// (a plain override). Quote a string that holds a top-level comma:
// `description='a, b'`. In the YAML block a YAML list gives the values
// directly: `model.hidden: [[28, 20], [32, 16]]`.
//
// Linked keys: `model.input_delays+model.feedback_delays=2,4,6` is one
// parameter whose value sets every key joined by '+' (seed 002 varies "input
// and feedback delays" together), so a grid has 3 points, not 9.
#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/core/rng.hpp"

namespace cnclab {

// "a.b+c.d" -> {"a.b", "c.d"}; a plain key -> {key}.
std::vector<std::string> linked_keys(const std::string& key);

struct SweepParameter {
  enum class Kind { values, int_range, uniform, log_uniform };
  std::string key;   // dotted config key, e.g. trainer.learning_rate; k1+k2 links keys
  std::string text;  // the values as written, for messages
  Kind kind = Kind::values;
  std::vector<YAML::Node> values;              // Kind::values
  std::int64_t first = 0, last = 0, step = 1;  // Kind::int_range (inclusive)
  double low = 0, high = 0;                    // uniform, log_uniform

  // values and int_range can be enumerated (grid); the others only sampled.
  bool enumerable() const { return kind == Kind::values || kind == Kind::int_range; }
  std::vector<YAML::Node> enumerate() const;
  // One value drawn with `rng` (uniformly among the enumerable values).
  YAML::Node sample(Rng& rng) const;
};

// Parses the values of `key` (grammar above). A single plain value is not a
// sweep: nullopt. ConfigError naming key and text on an empty list, unknown
// function, bad bounds (log range with lo <= 0, lo >= hi, step < 1).
std::optional<SweepParameter> parse_sweep_values(const std::string& key, const std::string& text);

enum class SweepMethod { grid, random, tpe, cmaes, nsga2, qmc };
// "grid", "random", "tpe", ...; and back (nullopt for another name).
const char* to_string(SweepMethod method);
std::optional<SweepMethod> parse_sweep_method(const std::string& name);
// tpe, cmaes, nsga2, qmc: trials asked of Optuna one by one (model_search.hpp).
bool model_based(SweepMethod method);

// Early stopping of hopeless trials (model-based methods only): Optuna's
// pruner of that name, given the validation objective every `report_every`
// epochs. options: the pruner's integer arguments by name (median:
// n_startup_trials, n_warmup_steps, interval_steps; successive_halving:
// min_resource, reduction_factor, min_early_stopping_rate; hyperband:
// min_resource, max_resource, reduction_factor); Optuna's defaults otherwise.
struct SweepPruner {
  std::string name = "none";  // none | median | successive_halving | hyperband
  std::map<std::string, std::int64_t> options;
};

// The quantity a sweep ranks trials by.
struct Objective {
  std::string metric;     // a stored metric of the experiment ("validation.rmse")
  bool maximize = false;  // false: lower is better
};

struct SweepSpec {
  // grid: the cartesian product of the enumerable parameters (first
  // parameter varies slowest). random: `trials` points, each value drawn from
  // its own stream derive_seed(seed, "sweep/<key>/<sample index>"), so adding
  // a parameter or more trials never changes the values drawn before.
  // Default: random when a parameter is continuous or trials is set, else grid.
  std::optional<SweepMethod> method;
  std::size_t trials = 0;             // random: number of points (>= 1)
  std::optional<std::uint64_t> seed;  // random: sampling seed; default: the experiment seed
  // Runs per point: repeat 0 uses the trial's own seed, repeat r >= 1 the
  // seed derive_seed(seed, "repeat/<r>"), so raising `repeats` keeps (and
  // resumes past) the runs already done. Points report mean ± std (n - 1).
  std::size_t repeats = 1;
  // Default: the validation value of the experiment's first metric,
  // maximised if it is r2 (resolve_objective, sweep_plan.hpp).
  std::optional<Objective> objective;
  std::vector<SweepParameter> parameters;  // in order of appearance
  // Model-based methods only. `trials` is the study's number of complete or
  // pruned trials; `seed` the sampler's seed.
  SweepPruner pruner;
  // The sampler's own options (Optuna's keyword arguments, e.g. tpe's
  // multivariate: true, constant_liar: true, n_startup_trials: 5), as YAML
  // scalar text by name; the Optuna helper checks names and types. Empty:
  // Optuna's defaults (qmc: scrambled).
  std::map<std::string, std::string> sampler;
  std::size_t report_every = 1;  // epochs between reports to the pruner (>= 1)
  // Several objectives (metric and mode each): Optuna optimises them
  // together (nsga2, tpe) and the summary lists the Pareto front; the first
  // ranks the points. Empty: `objective` alone.
  std::vector<Objective> objectives;

  SweepMethod resolved_method() const;
  // ConfigError on: no parameters, repeats 0, random without trials, a
  // continuous parameter in a grid.
  void validate() const;
  // Adds or replaces (same key, keeping its position) a parameter.
  void set(SweepParameter parameter);
};

// "validation.rmse", "rmse:min", "validation.r2:max"; ConfigError otherwise
// (the name is resolved by resolve_objective, sweep_plan.hpp).
Objective parse_objective(const std::string& text);

// Command-line words after the experiment file: `key=value` with one plain
// value are overrides, with a sweep grammar value sweep parameters.
struct SweepArguments {
  std::vector<std::string> overrides;
  std::vector<SweepParameter> parameters;
};
SweepArguments split_sweep_arguments(const std::vector<std::string>& words);

// The `sweep:` block of `file` (after includes and the plain `overrides`, so
// `sweep.repeats=3` works, and after `profile`, so a profile can shrink the
// sweep); an absent block gives an empty spec. Strict: unknown keys and bad
// values are ConfigErrors naming file:line:col.
SweepSpec read_sweep_block(const std::filesystem::path& file,
                           const std::vector<std::string>& overrides,
                           const std::string& profile = {});

class ConfigReader;
// The same block from an open document (`s` is the `sweep:` section; a
// `kind: sweep` job file's block, sweep_job.hpp). Marks what it reads.
SweepSpec read_sweep_section(const ConfigReader& s);

// One entry of a sweep block's `parameters` map: a YAML list of values, or a
// values text (the grammar above), or one value (a fixed setting).
// ConfigError with the broken rule (the caller adds where).
SweepParameter parse_sweep_parameter(const std::string& key, const YAML::Node& node);

}  // namespace cnclab
