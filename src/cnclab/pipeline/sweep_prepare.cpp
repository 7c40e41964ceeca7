#include "cnclab/pipeline/sweep_prepare.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/core/override.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/profiles.hpp"
#include "cnclab/sweep/sweep_job.hpp"
#include "cnclab/sweep/sweep_spec.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// What `cnclab sweep FILE` sweeps: FILE (a training experiment and its
// optional `sweep:` block), or for a `kind: sweep` job file the experiment it
// names, with the job's overrides and sweep block, into the job's folder
// results/<job name>/sweep-<plan hash> (so `reproduce` finds the trials).
struct SweepTarget {
  fs::path experiment;
  std::vector<std::string> overrides;  // the job's, then the command line's
  SweepSpec spec;                      // before the command line's changes
  std::string folder;                  // results/<folder>/; empty: the plan's experiment
  std::size_t jobs = 0;
};

SweepTarget sweep_target(const fs::path& file, const SweepArguments& args,
                         const SweepCommandOptions& o) {
  check_profile(file, o.common.profile);
  SweepTarget t;
  if (experiment_kind(file) == "sweep") {
    const SweepJob job = load_sweep_job(file, {}, o.common.profile);
    t.experiment = job.experiment;
    t.overrides = job.overrides;
    t.spec = job.sweep;
    t.folder = job.name;
    t.jobs = job.jobs;
  } else {
    t.experiment = file;
    t.spec = read_sweep_block(file, args.overrides, o.common.profile);
  }
  t.overrides.insert(t.overrides.end(), args.overrides.begin(), args.overrides.end());
  return t;
}

SweepSpec resolve_spec(SweepSpec spec, const SweepArguments& args, const SweepCommandOptions& o) {
  // A plain command-line value fixes a key the block sweeps.
  for (const auto& text : args.overrides) {
    const std::string key = parse_override(text).dotted_key();
    std::erase_if(spec.parameters, [&](const SweepParameter& p) { return p.key == key; });
  }
  for (const auto& p : args.parameters) spec.set(p);
  if (o.repeats) spec.repeats = *o.repeats;
  if (o.trials) spec.trials = *o.trials;
  if (o.sweep_seed) spec.seed = *o.sweep_seed;
  if (o.objective) spec.objective = parse_objective(*o.objective);
  if (o.method) {
    const auto method = parse_sweep_method(*o.method);
    if (!method) {
      throw ConfigError("--method " + *o.method +
                        ": must be one of: grid, random, tpe, cmaes, nsga2, qmc");
    }
    spec.method = *method;
  }
  return spec;
}

}  // namespace

PreparedSweep prepare_sweep(const fs::path& experiment, const std::vector<std::string>& words,
                            std::optional<std::uint64_t> seed, const SweepCommandOptions& o) {
  const SweepArguments args = split_sweep_arguments(words);
  const SweepTarget target = sweep_target(experiment, args, o);
  const SweepSpec spec = resolve_spec(target.spec, args, o);
  SweepExecuteOptions exec;
  exec.common = o.common;
  exec.jobs = o.jobs != 0 ? o.jobs : target.jobs;
  exec.trial_timeout = o.trial_timeout;
  exec.retry_failed = o.retry_failed;
  exec.rerun = o.rerun;
  exec.trial_ids = o.trial_ids;
  if (!o.shard.empty()) std::tie(exec.shard, exec.shards) = parse_shard(o.shard);
  SweepPlan plan = plan_sweep(target.experiment, target.overrides, seed, spec, o.common.profile);
  const std::string folder = target.folder.empty() ? plan.experiment : target.folder;
  fs::path dir =
      o.dir.empty() ? o.common.results_dir / folder / ("sweep-" + plan.hash().substr(0, 8)) : o.dir;
  return {std::move(plan),
          std::move(dir),
          std::move(exec),
          target.folder,
          spec,
          {target.experiment, target.overrides, seed, o.common.profile}};
}

}  // namespace cnclab
