#include "cnclab/sweep/sweep_execute.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <iostream>
#include <map>
#include <optional>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/core/progress.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/experiment_graph.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/nn/metrics.hpp"
#include "cnclab/sweep/trial_pool.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

std::string trial_text(const SweepPlan& plan, const PlannedTrial& t) {
  return point_text(plan.keys, t.values) +
         (plan.repeats > 1 ? " repeat " + std::to_string(t.repeat) : "");
}

// --regenerate: regenerates every dataset the trials need once, here, before
// the trials start (they then hit the cache). Without it the trials obtain
// their datasets themselves, in parallel, each missing one produced once
// under the cache's lock. A dataset that cannot be made is left to the
// trials, which record the error.
void regenerate_datasets(const SweepPlan& plan, const std::vector<std::size_t>& todo,
                         const CommandOptions& o, std::ostream* log) {
  std::set<std::string> seen;
  for (std::size_t i : todo) {
    const ExperimentSpec& spec = plan.trials[i].experiment->spec;
    const std::uint64_t seed = generator_seed(spec);
    const std::string key = spec.dataset.generator->name() +
                            spec.dataset.generator->options_yaml() + std::to_string(seed);
    if (!seen.insert(key).second) continue;
    try {
      StagedProgress generation("dataset " + spec.dataset.generator->name(), log ? *log : std::cerr,
                                {log && !o.quiet ? ProgressMode::automatic : ProgressMode::quiet});
      obtain_dataset(spec.dataset, seed, o.datasets_dir, log, true, generation.callback());
    } catch (const Error&) {
    }
  }
}

// Trials with init_from/needs whose upstream results changed since they ran
// are run again (the experiment graph's rule, experiment_graph.hpp); their
// outcome is reset to missing. Returns how many.
std::size_t invalidate_stale(const SweepPlan& plan, const std::vector<std::size_t>& mine,
                             const fs::path& results_dir, std::vector<TrialOutcome>& outcomes) {
  std::map<fs::path, std::optional<CurrentUpstream>> current;  // per upstream file
  std::size_t stale = 0;
  for (std::size_t i : mine) {
    if (!outcomes[i].done()) continue;
    std::vector<CurrentUpstream> upstream;
    for (const auto& file : upstream_files(plan.trials[i].experiment->spec)) {
      auto it = current.find(file);
      if (it == current.end()) {
        std::optional<CurrentUpstream> now;
        try {
          const UpstreamResult up =
              load_upstream(file, results_dir, plan.trials[i].experiment->spec.profile);
          now = CurrentUpstream{up.experiment.spec.name, result_identity(up.record)};
        } catch (const IoError&) {
          // Missing upstream: keep the trial's result (a re-run could only fail).
        }
        it = current.emplace(file, now).first;
      }
      if (it->second) upstream.push_back(*it->second);
    }
    if (!upstream.empty() && !staleness(outcomes[i].upstream, upstream).empty()) {
      outcomes[i] = TrialOutcome{};
      ++stale;
    }
  }
  return stale;
}

// Trials share results with the result store (result_store.hpp): a trial is
// an experiment with a resolved config, and its id is that config's hash, so
// the result `cnclab run` would write for the same config is the trial's
// result. Seed 002's studies train one configuration (12 neurons, 4 delays,
// seed 1, two-stage) in the plain experiment and in both sweeps; it is
// trained once. Only trials without upstream results share: theirs would
// also need the upstream check of invalidate_stale.
bool shares_with_store(const PlannedTrial& trial) {
  return upstream_files(trial.experiment->spec).empty();
}

// The store's complete result of the trial's config, if any (a file that is
// not one is left to the trial, which then writes its own).
std::optional<fs::path> stored_result(const ResultStore& store, const PlannedTrial& trial) {
  try {
    const auto r = store.existing(result_key(*trial.experiment));
    if (r && r->complete()) return r->file;
  } catch (const IoError&) {
  }
  return std::nullopt;
}

// Takes the store's results of trials still to run; returns the trials that
// remain to run.
std::vector<std::size_t> take_stored_results(const SweepPlan& plan, const fs::path& dir,
                                             const ResultStore& store,
                                             std::vector<std::size_t> todo,
                                             std::vector<TrialOutcome>& outcomes) {
  std::vector<std::size_t> remaining;
  for (std::size_t i : todo) {
    const PlannedTrial& t = plan.trials[i];
    const auto file = shares_with_store(t) ? stored_result(store, t) : std::nullopt;
    if (!file) {
      remaining.push_back(i);
      continue;
    }
    try {
      copy_file_atomically(*file, trial_result_path(dir, t.id));
    } catch (const IoError&) {
      remaining.push_back(i);  // the trial makes its own
      continue;
    }
    std::error_code ec;
    fs::remove(trial_error_path(dir, t.id), ec);
    outcomes[i] = read_trial_outcome(dir, t);
  }
  return remaining;
}

// A trial that completed becomes the store's result of its config unless
// the store already has a file there (never replaced: it may be in use).
// A failure only costs the sharing: a warning to `note`.
void publish_to_store(const ResultStore& store, const PlannedTrial& trial,
                      const fs::path& trial_file, std::ostream* note) {
  if (!shares_with_store(trial)) return;
  const fs::path target = store.path_of(result_key(*trial.experiment));
  std::error_code ec;
  if (fs::exists(target, ec)) return;
  try {
    copy_file_atomically(trial_file, target);
  } catch (const IoError& e) {
    if (note)
      *note << "warning: trial " << trial.id << " not shared with the store: " << e.what() << "\n";
  }
}

// The trials of `mine` named in `ids` (plan order).
std::vector<std::size_t> listed_trials(const SweepPlan& plan, const std::vector<std::size_t>& mine,
                                       const std::vector<std::string>& ids) {
  std::set<std::string> wanted(ids.begin(), ids.end());
  std::vector<std::size_t> listed;
  for (std::size_t i : mine) {
    if (wanted.erase(plan.trials[i].id)) listed.push_back(i);
  }
  if (!wanted.empty()) {
    throw ConfigError("--trial-ids: " + *wanted.begin() + " is not a trial of this sweep" +
                      (mine.size() < plan.trials.size() ? " (or of this shard)" : "") +
                      "; the ids are listed in its sweep.yaml");
  }
  return listed;
}

}  // namespace

SweepExecution execute_sweep(const SweepPlan& plan, const fs::path& dir,
                             const SweepExecuteOptions& o, std::ostream* note) {
  SweepExecution ex;
  ex.outcomes = read_trial_outcomes(dir, plan);
  ex.mine = shard_trials(plan.trials.size(), o.shard, o.shards);
  if (!o.trial_ids.empty()) ex.mine = listed_trials(plan, ex.mine, o.trial_ids);
  const std::size_t stale = invalidate_stale(plan, ex.mine, o.common.results_dir, ex.outcomes);
  std::vector<std::size_t> todo;
  for (std::size_t i : ex.mine) {
    const bool retry = o.retry_failed && ex.outcomes[i].status == TrialOutcome::Status::failed;
    if (o.rerun || retry || !ex.outcomes[i].done()) todo.push_back(i);
  }
  const ResultStore store(o.common.results_dir);
  std::size_t taken = 0;
  if (!o.rerun) {
    const std::size_t before = todo.size();
    todo = take_stored_results(plan, dir, store, std::move(todo), ex.outcomes);
    taken = before - todo.size();
  }
  const std::size_t jobs = o.jobs > 0 ? o.jobs : available_cores();
  if (note) {
    *note << "sweep " << dir.string() << ": " << plan.trials.size() << " trials";
    if (o.shards > 1)
      *note << ", shard " << o.shard << "/" << o.shards << " has " << ex.mine.size();
    if (plan.merged_duplicates)
      *note << " (" << plan.merged_duplicates << " duplicate samples merged)";
    if (stale) *note << "; " << stale << " to run again (upstream results changed)";
    if (taken) *note << "; " << taken << " taken from the results store";
    *note << "; " << ex.mine.size() - todo.size() << " already done, running " << todo.size()
          << " with " << std::min(jobs, std::max<std::size_t>(todo.size(), 1)) << " job(s)\n";
    if (const std::string w = objective_warning(plan); !w.empty())
      *note << "warning: " << w << "\n";
  }
  if (o.common.regenerate) regenerate_datasets(plan, todo, o.common, note);

  std::vector<TrialJob> pool_jobs;
  for (std::size_t i : todo) {
    pool_jobs.push_back({pool_jobs.size(),
                         &*plan.trials[i].experiment,
                         trial_result_path(dir, plan.trials[i].id),
                         trial_error_path(dir, plan.trials[i].id),
                         {}});
  }
  PoolOptions pool;
  pool.jobs = jobs;
  pool.run.results_dir = o.common.results_dir;
  pool.run.datasets_dir = o.common.datasets_dir;
  pool.trial_timeout_seconds = o.trial_timeout;
  ex.ran = todo.size();
  // Trials run silently (their output would interleave), so a log shows the
  // sweep is alive: after 8 s without a line, "[sweep] 3/11 done, 1m05s"
  // (a line at least every 10 s with the pool's ~1 s tick to spare).
  using Clock = std::chrono::steady_clock;
  constexpr std::chrono::seconds kHeartbeat{8};
  const auto started = Clock::now();
  auto last_line = started;
  if (note) {
    pool.on_tick = [&] {
      const auto now = Clock::now();
      if (now - last_line < kHeartbeat) return;
      *note << "[sweep] " << ex.finished << "/" << todo.size() << " done, "
            << Progress::format_duration(std::chrono::duration<double>(now - started).count())
            << std::endl;
      last_line = now;
    };
  }
  ex.stopped = run_trial_pool(pool_jobs, pool, [&](std::size_t job, const TrialExit& exit) {
    const std::size_t i = todo[job];
    if (exit.kind == TrialExit::Kind::interrupted) return;
    ex.outcomes[i] = read_trial_outcome(dir, plan.trials[i]);
    if (!ex.outcomes[i].result_file.empty()) {
      std::error_code ec;
      fs::remove(trial_error_path(dir, plan.trials[i].id), ec);  // a stale note of an earlier try
    }
    if (ex.outcomes[i].status == TrialOutcome::Status::complete) {
      publish_to_store(store, plan.trials[i], trial_result_path(dir, plan.trials[i].id), note);
    }
    ++ex.finished;
    if (!note) return;
    last_line = Clock::now();
    const TrialOutcome& r = ex.outcomes[i];
    *note << "[" << ex.finished << "/" << todo.size() << "] " << plan.trials[i].id << " "
          << trial_text(plan, plan.trials[i]) << ": ";
    if (r.status == TrialOutcome::Status::complete) {
      const auto it = r.metrics.find(plan.objective.metric);
      *note << plan.objective.metric << " "
            << (it == r.metrics.end() ? std::string("?") : format_metric(it->second)) << "\n";
    } else {
      *note << to_string(r.status) << ": " << (r.reason.empty() ? exit.message : r.reason) << "\n";
    }
  });
  // Drained (SIGUSR1) after every trial had started: nothing was left out.
  if (ex.stopped == SIGUSR1 && ex.finished == ex.ran) ex.stopped = 0;
  return ex;
}

}  // namespace cnclab
