#include "cnclab/pipeline/sweep_command.hpp"

#include "cnclab/core/error.hpp"
#include "cnclab/data/dataset_cache.hpp"
#include "cnclab/io/atomic_file.hpp"
#include "cnclab/report/sweep_report.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

int summary_exit_code(const SweepSummary& s) {
  return s.failed + s.errors + s.missing == 0 ? 0 : 1;
}

// summary.h5 of a model-based sweep's study, and its table.
SweepSummary write_study_summary(const ModelSearch& s, const fs::path& dir, const std::string& name,
                                 std::ostream& out) {
  const SweepSummary summary = summarize(s.plan, s.outcomes);
  write_summary(dir / "summary.h5", s.plan, s.outcomes, summary, &s.findings);
  print_summary(out, s.plan, s.outcomes, summary, dir, name);
  print_search_findings(out, s.findings);
  return summary;
}

// A model-based sweep (model_search.hpp): the study runs to its count; exit 0
// when it has it, 1 otherwise.
int model_search_command(const PreparedSweep& prepared, const SweepCommandOptions& o,
                         std::ostream& out, std::ostream& log) {
  if (prepared.exec.shards > 1 || !o.trial_ids.empty()) {
    throw ConfigError("sweep method " + prepared.plan.method +
                      ": --shard and --trial-ids split a fixed plan; a study's workers share its "
                      "journal instead (run the same command in each, e.g. as Slurm array tasks)");
  }
  clean_stale_partials({o.common.results_dir, prepared.dir, o.common.datasets_dir}, log);
  const ModelSearch s =
      run_model_search(prepared.plan, prepared.spec, prepared.source, prepared.dir, prepared.exec,
                       o.common.quiet ? nullptr : &log);
  if (s.stopped != 0) {
    out << "interrupted by signal " << s.stopped
        << "; run the same command again to continue the study (finished trials are kept)\n";
    return 128 + s.stopped;
  }
  const SweepSummary summary = write_study_summary(s, prepared.dir, prepared.name, out);
  out << "study: " << s.finished << " of " << prepared.spec.trials << " trials complete or pruned ("
      << summary.pruned << " pruned, not ranked); " << s.ran << " point(s) trained now, "
      << s.reused << " reused\n";
  out << "summary: " << (prepared.dir / "summary.h5").string() << "\n";
  return s.finished >= prepared.spec.trials ? 0 : 1;
}

}  // namespace

int sweep_command(const fs::path& experiment, const std::vector<std::string>& words,
                  std::optional<std::uint64_t> seed, const SweepCommandOptions& o,
                  std::ostream& out, std::ostream& log) {
  const PreparedSweep prepared = prepare_sweep(experiment, words, seed, o);
  const SweepPlan& plan = prepared.plan;
  const fs::path& dir = prepared.dir;
  const std::size_t shard = prepared.exec.shard, shards = prepared.exec.shards;
  if (model_based(plan)) return model_search_command(prepared, o, out, log);
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
  if (model_based(plan)) {
    // The study's trials as they stand, nothing asked. Its failed points
    // were asked again (model_search.hpp): they do not fail the merge.
    const ModelSearch s = read_study(plan, dir);
    const SweepSummary summary = write_study_summary(s, dir, "", out);
    out << "study: " << s.finished << " trials complete or pruned (" << summary.pruned
        << " pruned, not ranked)\nsummary: " << (dir / "summary.h5").string() << "\n";
    return 0;
  }
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
