#include "cnclab/pipeline/reproduce_run.hpp"

#include <algorithm>
#include <chrono>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <iterator>
#include <optional>
#include <set>

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/experiment/experiment_graph.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/result_store.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/experiment/upstream.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/pipeline/run_options.hpp"
#include "cnclab/sweep/trial_pool.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

// Where an experiment of the graph stands.
struct NodeState {
  enum class Stage { waiting, running, done } stage = Stage::waiting;
  std::optional<RunRecord> record;  // its current result, once done
  std::string problem;              // done without a usable result: why
  std::optional<ReproduceRow> row;  // its line of the summary, once done
  std::string why;                  // running: why it runs
  std::chrono::steady_clock::time_point started;
};

// The graph's scheduler: decides for each experiment whose upstream are done
// whether its result is current, runs the others through the trial pool and
// records one summary row per experiment.
class GraphRun {
 public:
  GraphRun(const std::vector<GraphNode>& graph, std::vector<JobPrework> prework,
           const CommandOptions& options, std::ostream& log)
      : graph_(graph),
        prework_(std::move(prework)),
        options_(options),
        run_(run_options(options, log)),
        store_(options.results_dir, options.profile),
        log_(run_.log),
        state_(graph.size()),
        prework_started_(prework_.size()) {}

  // Runs what needs running; returns 0, or the signal that stopped it.
  int run(std::size_t jobs) {
    PoolOptions pool;
    pool.jobs = jobs;
    pool.run = run_;
    pool.run.regenerate_dataset = false;  // done once per dataset in start()
    // One experiment at a time: its progress may go to the log as it runs.
    pool.trial_output = jobs == 1 && log_;
    if (!pool.trial_output) pool.on_tick = [this] { heartbeat(); };
    return run_trial_pool([this] { return next_ready(); }, pool,
                          [this](std::size_t i, const TrialExit& exit) { finished(i, exit); });
  }

  // The summary rows in graph order (an experiment stopped by a signal says so).
  std::vector<ReproduceRow> rows() const {
    std::vector<ReproduceRow> out;
    for (std::size_t i = 0; i < graph_.size(); ++i) {
      out.push_back(
          state_[i].row.value_or(ReproduceRow{display_name(i), "not run", "interrupted", "", ""}));
    }
    return out;
  }

  int exit_code() const { return exit_code_; }

 private:
  std::string display_name(std::size_t i) const {
    const GraphNode& node = graph_[i];
    if (!node.experiment) return node.file.string();
    // Experiments not asked for, added because others need them, say so.
    return node.experiment->spec.name + (node.requested ? "" : " (upstream)");
  }

  void finish(std::size_t i, ReproduceRow row, std::string problem = {}) {
    state_[i].stage = NodeState::Stage::done;
    state_[i].row = std::move(row);
    state_[i].problem = std::move(problem);
  }

  // Experiment i has no result: a configuration error (exit 2) or another
  // error (exit 1), with the text that says why.
  void fail(std::size_t i, bool config_error, const std::string& why, const std::string& detail) {
    finish(i, {display_name(i), config_error ? "CONFIG ERROR" : "ERROR", why, detail, ""},
           config_error ? "configuration error" : "error");
    exit_code_ = config_error ? 2 : std::max(exit_code_, 1);
  }

  // The jobs' prework first (a dataset takes one slot for minutes, and the
  // jobs after the graph wait for it), then the next experiment to train
  // whose upstream are done; experiments that are current, blocked or broken
  // are settled on the way.
  std::optional<TrialJob> next_ready() {
    if (next_prework_ < prework_.size()) return start_prework(next_prework_++);
    for (std::size_t i = 0; i < graph_.size(); ++i) {
      if (state_[i].stage != NodeState::Stage::waiting) continue;
      bool upstream_done = true;
      for (std::size_t j : graph_[i].upstream) {
        upstream_done = upstream_done && state_[j].stage == NodeState::Stage::done;
      }
      if (!upstream_done) continue;
      if (const std::optional<std::string> why = decide(i)) {
        if (std::optional<TrialJob> job = start(i, *why)) return job;
      }
    }
    return std::nullopt;
  }

  // Why experiment i must run, or nullopt when it was settled here (reused,
  // blocked by its upstream, failed to load).
  std::optional<std::string> decide(std::size_t i) {
    const GraphNode& node = graph_[i];
    if (!node.experiment) {
      fail(i, node.config_error, node.load_error, "");
      state_[i].problem = "failed to load";
      return std::nullopt;
    }
    std::vector<CurrentUpstream> upstream;
    for (std::size_t j : node.upstream) {
      const std::string up_name =
          graph_[j].experiment ? graph_[j].experiment->spec.name : graph_[j].file.string();
      if (!state_[j].record) {
        finish(i,
               {display_name(i), "skipped",
                "upstream " + up_name + " has no result (" + state_[j].problem + ")", "", ""},
               "skipped");
        exit_code_ = std::max(exit_code_, 1);
        return std::nullopt;
      }
      upstream.push_back({up_name, result_identity(*state_[j].record)});
    }
    if (options_.force) return "--force";
    CurrentResult current = current_result(*node.experiment, upstream, store_);
    if (!current.record) return current.why;
    state_[i].record = std::move(current.record);
    settle(i, "reused", "config and upstream results unchanged");
    return std::nullopt;
  }

  // Experiment i's trial, or nullopt when what it needs first failed (its
  // row says why).
  std::optional<TrialJob> start(std::size_t i, const std::string& why) {
    const LoadedExperiment& exp = *graph_[i].experiment;
    const fs::path path = result_path(exp, options_.results_dir);
    try {
      // --regenerate: each dataset once, here; the trials then hit the cache.
      if (options_.regenerate) {
        const std::uint64_t seed = generator_seed(exp.spec);
        const fs::path file = dataset_cache_file(exp.spec.dataset, seed, options_.datasets_dir);
        if (regenerated_.insert(file).second) {
          StagedProgress generation("dataset " + exp.spec.dataset.generator->name(),
                                    log_ ? *log_ : std::cerr,
                                    {log_ ? ProgressMode::automatic : ProgressMode::quiet});
          obtain_dataset(exp.spec.dataset, seed, options_.datasets_dir, log_, true,
                         generation.callback());
        }
      }
      fs::create_directories(path.parent_path());
    } catch (const std::exception& e) {
      fail(i, dynamic_cast<const ConfigError*>(&e) != nullptr, why, e.what());
      return std::nullopt;
    }
    NodeState& s = state_[i];
    s.stage = NodeState::Stage::running;
    s.why = why;
    s.started = std::chrono::steady_clock::now();
    ++started_;
    if (log_) *log_ << "[run " << started_ << "] " << display_name(i) << " (" << why << ")\n";
    last_log_ = s.started;
    return TrialJob{i, &exp, path, error_note(path), {}};
  }

  static fs::path error_note(const fs::path& result) { return result.string() + ".error"; }

  // Prework k runs in the pool as index graph_.size() + k.
  TrialJob start_prework(std::size_t k) {
    prework_started_[k] = std::chrono::steady_clock::now();
    if (log_) *log_ << "[prepare] " << prework_[k].what << ", beside the training\n";
    TrialJob job;
    job.index = graph_.size() + k;
    job.task = prework_[k].run;
    job.error_file = error_note(prework_[k].key);
    return job;
  }

  // A failed prework is only logged: the job meets the same error when it
  // runs and reports it in its row.
  void prework_finished(std::size_t k, const TrialExit& exit) {
    prework_done_.insert(k);
    const std::string text = read_note(error_note(prework_[k].key));
    if (!log_ || exit.kind == TrialExit::Kind::interrupted) return;
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - prework_started_[k])
            .count();
    *log_ << "[prepared] " << prework_[k].what;
    if (exit.kind == TrialExit::Kind::result) {
      *log_ << " in " << std::fixed << std::setprecision(1) << seconds << " s" << std::defaultfloat;
    } else if (exit.kind == TrialExit::Kind::error) {
      *log_ << ": failed (" << (text.empty() ? exit.message : text) << "); its job will say why";
    }
    *log_ << "\n";
    last_log_ = std::chrono::steady_clock::now();
  }

  void finished(std::size_t i, const TrialExit& exit) {
    if (i >= graph_.size()) return prework_finished(i - graph_.size(), exit);
    NodeState& s = state_[i];
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - s.started).count();
    const fs::path path = result_path(*graph_[i].experiment, options_.results_dir);
    if (exit.kind == TrialExit::Kind::interrupted) {
      s.stage = NodeState::Stage::done;  // the pool starts nothing more; rows() says so
      return;
    }
    if (exit.kind == TrialExit::Kind::error) {
      const std::string text = read_note(error_note(path));
      fail(i, exit.config_error, s.why, text.empty() ? exit.message : text);
    } else {
      try {
        s.record = read_result(path);
        settle(i, "ran", s.why);
      } catch (const Error& e) {
        fail(i, false, s.why, e.what());
      }
    }
    if (log_) {
      *log_ << "[done " << ++finished_ << "/" << started_ << "] " << display_name(i) << " "
            << s.row->action << " in " << std::fixed << std::setprecision(1) << seconds << " s"
            << std::defaultfloat;
      if (s.record) {
        for (const auto& w : s.record->warnings) *log_ << " (warning: " << w << ")";
      }
      *log_ << "\n";
      last_log_ = std::chrono::steady_clock::now();
    }
  }

  // Long runs say they are still running: every kHeartbeat without another
  // line, "[running] NAME 2m05s, ..." (the trials themselves are silent).
  // 8 s: a log that is not a terminal shows a line at least every 10 s, with
  // the pool's tick and a loaded machine's lateness to spare (at 10 s the
  // measured gaps were 10.01-10.02 s).
  void heartbeat() {
    constexpr std::chrono::seconds kHeartbeat{8};
    const auto now = std::chrono::steady_clock::now();
    if (!log_ || now - last_log_ < kHeartbeat) return;
    std::string line;
    const auto add = [&](const std::string& name, std::chrono::steady_clock::time_point started) {
      const auto s = std::chrono::duration_cast<std::chrono::seconds>(now - started);
      line += (line.empty() ? "" : ", ") + name + " " + std::to_string(s.count() / 60) + "m" +
              (s.count() % 60 < 10 ? "0" : "") + std::to_string(s.count() % 60) + "s";
    };
    for (std::size_t i = 0; i < graph_.size(); ++i) {
      if (state_[i].stage == NodeState::Stage::running) add(display_name(i), state_[i].started);
    }
    for (std::size_t k = 0; k < next_prework_; ++k) {
      if (!prework_done_.count(k)) add(prework_[k].what, prework_started_[k]);
    }
    if (!line.empty()) *log_ << "[running] " << line << "\n";
    last_log_ = now;
  }

  // Experiment i has its result in state_[i].record (ran or reused): its row.
  // A diverged training is a failure unless the experiment allows it
  // (may_diverge, spec.hpp).
  void settle(std::size_t i, const std::string& action, const std::string& why) {
    const RunRecord& r = *state_[i].record;
    const fs::path path = result_path(*graph_[i].experiment, options_.results_dir);
    if (r.provenance.status == "complete") {
      // A degenerate network (run_warnings.hpp) is complete, but says so first.
      std::string detail = metrics_line(r.metrics);
      for (const auto& w : r.warnings) detail = "WARNING " + w + "; " + detail;
      finish(i, {display_name(i), action, why, detail, path.string()});
    } else if (graph_[i].experiment->spec.may_diverge) {
      finish(i, {display_name(i), action + ", diverged", why,
                 r.provenance.failure_reason + " (allowed: may_diverge)", path.string()});
    } else {
      finish(i, {display_name(i), action + ", FAILED", why, r.provenance.failure_reason,
                 path.string()});
      exit_code_ = std::max(exit_code_, 1);
    }
  }

  // The text of an error note a trial left (and the note removed), or "".
  static std::string read_note(const fs::path& note) {
    std::ifstream in(note);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    while (!text.empty() && text.back() == '\n') text.pop_back();
    std::error_code ec;
    fs::remove(note, ec);
    return text;
  }

  const std::vector<GraphNode>& graph_;
  const std::vector<JobPrework> prework_;  // the jobs' datasets, run before the graph's trainings
  const CommandOptions& options_;
  const RunOptions run_;     // the trials' options
  const ResultStore store_;  // where current results are found (reuse)
  std::ostream* log_;        // progress; null when quiet
  std::vector<NodeState> state_;
  std::set<fs::path> regenerated_;
  std::size_t next_prework_ = 0;
  std::vector<std::chrono::steady_clock::time_point> prework_started_;
  std::set<std::size_t> prework_done_;
  std::size_t started_ = 0, finished_ = 0;
  std::chrono::steady_clock::time_point last_log_ = std::chrono::steady_clock::now();
  int exit_code_ = 0;
};
}  // namespace

ReproduceRun run_reproduce(const ReproduceInputs& inputs, const CommandOptions& options,
                           std::ostream& log) {
  const std::vector<GraphNode> graph = load_graph(inputs.files, options.profile);
  GraphRun graph_run(graph, jobs_prework(inputs.jobs, options), options, log);
  clean_stale_partials({options.results_dir, options.datasets_dir}, log);
  const std::size_t parallel = options.jobs > 0 ? options.jobs : available_cores();
  if (!options.quiet) {
    log << "reproduce: " << graph.size() << " experiment(s) and " << inputs.jobs.size()
        << " job(s); training up to " << parallel << " at once\n";
  }
  ReproduceRun run;
  run.stopped = graph_run.run(parallel);
  run.rows = graph_run.rows();
  run.exit_code = graph_run.exit_code();
  if (run.stopped != 0) return run;
  // Jobs read training results: they run after the graph, in file order.
  const JobContext context{options, {}, options.quiet ? nullptr : &log};
  for (const auto& [file, kind] : inputs.jobs) {
    if (!options.quiet) log << "[" << kind.kind << "] " << file.string() << "\n";
    try {
      const JobReport r = kind.run(file, context);
      run.rows.push_back({r.name, r.action, r.why, r.detail, r.file});
      if (!r.report.empty()) run.reports += "\n" + r.report;
    } catch (const ConfigError& e) {
      run.rows.push_back({file.string(), "CONFIG ERROR", kind.kind + " job", e.what(), ""});
      run.exit_code = 2;
    } catch (const Error& e) {
      run.rows.push_back({file.string(), "ERROR", kind.kind + " job", e.what(), ""});
      run.exit_code = std::max(run.exit_code, 1);
    }
  }
  return run;
}

}  // namespace cnclab
