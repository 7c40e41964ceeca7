#include "cnclab/sweep/sweep_execute.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <deque>
#include <iostream>
#include <map>
#include <optional>
#include <set>
#include <thread>

#include "cnclab/core/error.hpp"
#include "cnclab/core/progress.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/experiment_graph.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/io/lock_file.hpp"
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

// Takes the store's result of the trial (a hard link in the sweep folder);
// false when the store has none or it cannot be linked or copied (the trial
// then makes its own).
bool take_stored_result(const PlannedTrial& t, const fs::path& dir, const ResultStore& store,
                        TrialOutcome& outcome) {
  const auto file = shares_with_store(t) ? stored_result(store, t) : std::nullopt;
  if (!file) return false;
  try {
    copy_file_atomically(*file, trial_result_path(dir, t.id));
  } catch (const IoError&) {
    return false;
  }
  std::error_code ec;
  fs::remove(trial_error_path(dir, t.id), ec);
  outcome = read_trial_outcome(dir, t);
  return true;
}

// The trial's files (result, error note) by identity: every writer replaces
// them by rename, so another inode means another write.
struct TrialFiles {
  std::uintmax_t result = 0, error = 0;  // inode numbers; 0: no such file
  bool operator==(const TrialFiles&) const = default;
};

TrialFiles trial_files(const fs::path& dir, const std::string& id) {
  const auto inode = [](const fs::path& p) -> std::uintmax_t {
    struct stat st {};
    return ::stat(p.c_str(), &st) == 0 ? static_cast<std::uintmax_t>(st.st_ino) : 0;
  };
  return {inode(trial_result_path(dir, id)), inode(trial_error_path(dir, id))};
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

// One writer per trial (sweep_execute.hpp): which of the trials to run this
// process takes, trial by trial, as pool slots free up.
class TrialClaims {
 public:
  TrialClaims(const SweepPlan& plan, const fs::path& dir, const SweepExecuteOptions& o,
              const ResultStore& store, std::vector<TrialOutcome>& outcomes, std::ostream* note)
      : plan_(plan), dir_(dir), o_(o), store_(store), outcomes_(outcomes), note_(note) {}

  // Remembers the trials' files as this process found them.
  void look(const std::vector<std::size_t>& todo) {
    for (std::size_t i : todo) seen_[i] = trial_files(dir_, plan_.trials[i].id);
  }

  // With trial i's lock held: whether it still needs to run here. Not when
  // another process wrote its files since look() and it is done now, nor
  // when the store has its result (taken, unless --rerun).
  bool still_to_run(std::size_t i) {
    const PlannedTrial& t = plan_.trials[i];
    if (trial_files(dir_, t.id) != seen_[i]) {
      outcomes_[i] = read_trial_outcome(dir_, t);
      if (outcomes_[i].done()) {
        ++by_others_;
        return false;
      }
    }
    if (!o_.rerun && take_stored_result(t, dir_, store_, outcomes_[i])) {
      ++taken_;
      return false;
    }
    return true;
  }

  // Takes the store's result of each trial of `todo` that has one and whose
  // lock is free (unless --rerun); returns the others, in order, for the pool.
  std::vector<std::size_t> take_stored(const std::vector<std::size_t>& todo) {
    std::vector<std::size_t> remaining;
    for (std::size_t i : todo) {
      const PlannedTrial& t = plan_.trials[i];
      if (o_.rerun || !shares_with_store(t) || !stored_result(store_, t)) {
        remaining.push_back(i);
        continue;
      }
      const auto lock = LockFile::try_lock(trial_lock_path(dir_, t.id));
      if (!lock || still_to_run(i)) remaining.push_back(i);
    }
    return remaining;
  }

  void queue(const std::vector<std::size_t>& todo) { queue_.assign(todo.begin(), todo.end()); }

  // The pool's next job: the next queued trial whose lock this process gets
  // and that still needs to run; when none is left but others hold some, a
  // task that waits until the first of them is released.
  std::optional<TrialJob> next() {
    while (!queue_.empty()) {
      const std::size_t i = queue_.front();
      queue_.pop_front();
      const PlannedTrial& t = plan_.trials[i];
      std::string holder;
      auto lock = LockFile::try_lock(trial_lock_path(dir_, t.id), &holder);
      if (!lock) {
        elsewhere_.push_back(i);
        if (note_ && reported_.insert(holder).second) {
          *note_ << "note: trial " << t.id << " is being run by another process ("
                 << LockFile::describe_holder(holder)
                 << "); this sweep runs the trials no one holds, then waits for it\n";
        }
        continue;
      }
      if (!still_to_run(i)) continue;  // the lock goes with it
      locks_.emplace(i, std::move(*lock));
      ++started_;
      return TrialJob{
          i, &*t.experiment, trial_result_path(dir_, t.id), trial_error_path(dir_, t.id), {}};
    }
    if (waiting_ || elsewhere_.empty()) return std::nullopt;
    waiting_ = true;
    const fs::path lock = trial_lock_path(dir_, plan_.trials[elsewhere_.front()].id);
    if (const std::string holder = LockFile::holder(lock); note_ && !holder.empty()) {
      *note_ << "note: waiting for " << elsewhere_.size()
             << " trial(s) another process is running (first: " << lock.string() << ", "
             << LockFile::describe_holder(holder)
             << "; if that process is gone, remove the file)\n";
    }
    TrialJob wait{kWaitJob, nullptr, {}, {}, [lock] {
                    while (LockFile::held(lock)) {
                      std::this_thread::sleep_for(std::chrono::milliseconds(200));
                    }
                  }};
    wait.timed = false;
    return wait;
  }

  // The wait task ended: the trials held elsewhere are tried again.
  void wait_ended() {
    waiting_ = false;
    queue_.insert(queue_.end(), elsewhere_.begin(), elsewhere_.end());
    elsewhere_.clear();
  }

  // Trial i ended here: its lock is released.
  void ended(std::size_t i) { locks_.erase(i); }

  // Trials queued or held elsewhere, not settled when the pool stopped.
  std::size_t unsettled() const { return queue_.size() + elsewhere_.size(); }
  std::size_t started() const { return started_; }
  std::size_t taken() const { return taken_; }
  std::size_t by_others() const { return by_others_; }

  static constexpr std::size_t kWaitJob = static_cast<std::size_t>(-1);

 private:
  const SweepPlan& plan_;
  const fs::path& dir_;
  const SweepExecuteOptions& o_;
  const ResultStore& store_;
  std::vector<TrialOutcome>& outcomes_;
  std::ostream* note_;
  std::map<std::size_t, TrialFiles> seen_;
  std::deque<std::size_t> queue_;
  std::vector<std::size_t> elsewhere_;  // held by another process when last tried
  std::map<std::size_t, LockFile> locks_;
  std::set<std::string> reported_;  // holders named in a note
  bool waiting_ = false;
  std::size_t started_ = 0, taken_ = 0, by_others_ = 0;
};

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
  TrialClaims claims(plan, dir, o, store, ex.outcomes, note);
  claims.look(todo);
  todo = claims.take_stored(todo);
  const std::size_t taken = claims.taken();
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
  claims.queue(todo);

  PoolOptions pool;
  pool.jobs = jobs;
  pool.run.results_dir = o.common.results_dir;
  pool.run.datasets_dir = o.common.datasets_dir;
  pool.trial_timeout_seconds = o.trial_timeout;
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
  const std::size_t others_before = claims.by_others();
  ex.stopped = run_trial_pool(
      [&] { return claims.next(); }, pool,
      [&](std::size_t i, const TrialExit& exit) {
        if (i == TrialClaims::kWaitJob) {
          claims.wait_ended();
          return;
        }
        if (exit.kind == TrialExit::Kind::interrupted) return claims.ended(i);
        ex.outcomes[i] = read_trial_outcome(dir, plan.trials[i]);
        if (!ex.outcomes[i].result_file.empty()) {
          std::error_code ec;
          fs::remove(trial_error_path(dir, plan.trials[i].id),
                     ec);  // a stale note of an earlier try
        }
        if (ex.outcomes[i].status == TrialOutcome::Status::complete) {
          publish_to_store(store, plan.trials[i], trial_result_path(dir, plan.trials[i].id), note);
        }
        claims.ended(i);
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
          *note << to_string(r.status) << ": " << (r.reason.empty() ? exit.message : r.reason)
                << "\n";
        }
      });
  ex.ran = claims.started();
  if (note && claims.by_others() > others_before) {
    *note << "note: " << claims.by_others() - others_before
          << " trial(s) were run by another process on this folder meanwhile\n";
  }
  // Drained (SIGUSR1) after every trial had started: nothing was left out.
  if (ex.stopped == SIGUSR1 && ex.finished == ex.ran && claims.unsettled() == 0) ex.stopped = 0;
  return ex;
}

}  // namespace cnclab
