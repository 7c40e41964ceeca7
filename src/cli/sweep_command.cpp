#include "cli/sweep_command.hpp"

#include <map>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/experiment_graph.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/profiles.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/report/sweep_report.hpp"
#include "cnclab/sweep/sweep_job.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"
#include "cnclab/sweep/trial_pool.hpp"

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
    if (*o.method != "grid" && *o.method != "random") {
      throw ConfigError("--method " + *o.method + ": must be one of: grid, random");
    }
    spec.method = *o.method == "grid" ? SweepMethod::grid : SweepMethod::random;
  }
  return spec;
}

int summary_exit_code(const SweepSummary& s) {
  return s.failed + s.errors + s.missing == 0 ? 0 : 1;
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
  return {std::move(plan), std::move(dir), std::move(exec), target.folder};
}

int sweep_command(const fs::path& experiment, const std::vector<std::string>& words,
                  std::optional<std::uint64_t> seed, const SweepCommandOptions& o,
                  std::ostream& out, std::ostream& log) {
  const PreparedSweep prepared = prepare_sweep(experiment, words, seed, o);
  const SweepPlan& plan = prepared.plan;
  const fs::path& dir = prepared.dir;
  const std::size_t shard = prepared.exec.shard, shards = prepared.exec.shards;
  store_plan(dir, plan);
  clean_stale_partials({o.common.results_dir, dir, o.common.datasets_dir}, log);

  const SweepExecution ex =
      execute_sweep(plan, dir, prepared.exec, o.common.quiet ? nullptr : &log);
  const std::vector<TrialOutcome>& outcomes = ex.outcomes;
  const std::vector<std::size_t>& mine = ex.mine;
  if (ex.stopped != 0) {
    out << "interrupted by signal " << ex.stopped << ": " << ex.finished << " of " << ex.ran
        << " trials finished; run the same command again to resume (finished trials are kept)\n";
    return 128 + ex.stopped;
  }

  if (shards > 1 || !o.trial_ids.empty()) {
    std::size_t ok = 0, bad = 0;
    for (std::size_t i : mine) (outcomes[i].status == TrialOutcome::Status::complete ? ok : bad)++;
    const std::string part = o.trial_ids.empty()
                                 ? "shard " + std::to_string(shard) + "/" + std::to_string(shards)
                                 : std::to_string(mine.size()) + " listed trials";
    out << part << " of " << dir.string() << ": " << ok << " complete, " << bad
        << " failed; when every shard is done: cnclab sweep merge " << dir.string() << "\n";
    return bad == 0 ? 0 : 1;
  }
  const SweepSummary summary = summarize(plan, outcomes);
  write_summary(dir / "summary.h5", plan, outcomes, summary);
  print_summary(out, plan, outcomes, summary, dir, prepared.name);
  out << "summary: " << (dir / "summary.h5").string() << "\n";
  return summary_exit_code(summary);
}

int sweep_merge_command(const fs::path& dir, std::ostream& out) {
  const SweepPlan plan = load_plan(dir);
  const std::vector<TrialOutcome> outcomes = read_trial_outcomes(dir, plan);
  const SweepSummary summary = summarize(plan, outcomes);
  write_summary(dir / "summary.h5", plan, outcomes, summary);
  print_summary(out, plan, outcomes, summary, dir);
  if (summary.missing) {
    out << summary.missing << " trial(s) have no result yet: run the missing shards (or the "
        << "sweep without --shard) into " << dir.string() << ", then merge again\n";
  }
  out << "summary: " << (dir / "summary.h5").string() << "\n";
  return summary_exit_code(summary);
}

}  // namespace cnclab
