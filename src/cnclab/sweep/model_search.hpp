#pragma once
// Model-based search (sweep methods tpe, cmaes, nsga2, qmc): the points are
// asked one by one of an Optuna study (optuna_helper.hpp) that lives in
// <sweep dir>/study.journal (Optuna's JournalFileStorage). Running the same
// sweep again continues the study until it has `trials` complete or pruned
// trials; Slurm array tasks (or any processes on the folder) each run their
// own helper against the shared journal, so one study spreads over them.
//
// Each Optuna trial is one point. Its trainings are ordinary sweep trials:
// result files trials/<id>.h5 whose id is the hash of the resolved config, as
// for grid and random search, so a sampled point equal to a finished trial's
// config reuses that result (nothing is trained again).
//
// Pruning and repeats (one rule): repeat 0 of a point reports the validation
// objective to the pruner every `report_every` epochs; when the pruner stops
// it, the point is pruned (its result keeps the history, status "pruned") and
// its other repeats are not run. A point that is not pruned runs its other
// repeats without pruning and is told the mean of the objective over them.
// A pruned point is not ranked (sweep_summary.hpp ranks complete trials).
//
// Reproducibility: with --jobs 1 (one worker), a fixed sampler seed gives the
// same sequence of trials. With more jobs or workers the sequence depends on
// the order in which trials finish, as in Optuna. Worker k of a Slurm array
// (SLURM_ARRAY_TASK_ID) seeds its sampler with seed + k, so workers do not
// draw the same first points; a worker that continues a study (a rerun, a
// resubmitted task) adds the number of trials already in the journal.
//
// A killed worker: the helper records the host and pid of the process
// holding each running trial; a starting worker fails the trials whose holder
// has ended (the lock-file rule of io/lock_file.hpp), and the study asks for
// new ones, so it still ends with the requested count.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/sweep/search_findings.hpp"
#include "cnclab/sweep/sweep_execute.hpp"
#include "cnclab/sweep/sweep_plan.hpp"
#include "cnclab/sweep/sweep_spec.hpp"
#include "cnclab/sweep/sweep_summary.hpp"

namespace cnclab {

// What the trials are made from: the experiment file, its overrides, the
// --seed option and the profile (as plan_sweep's).
struct SearchSource {
  std::filesystem::path experiment;
  std::vector<std::string> overrides;
  std::optional<std::uint64_t> seed;
  std::string profile;
};

struct ModelSearch {
  SweepPlan plan;                      // the header plan with the study's trials (number order)
  std::vector<TrialOutcome> outcomes;  // per plan trial
  SearchFindings findings;
  std::size_t finished = 0;  // complete + pruned trials in the study
  std::size_t ran = 0;       // points trained by this process
  std::size_t reused = 0;    // points whose results existed already
  std::size_t reaped = 0;    // trials failed because their worker had ended
  int stopped = 0;           // the signal that interrupted the search; 0: none
};

// The journal of the sweep in `dir`.
std::filesystem::path study_journal(const std::filesystem::path& dir);

// The complete and pruned trials of the study in `dir` (0 when it has no
// journal yet), after failing the trials whose worker on this host has
// ended: what `sweep --slurm` still has to submit workers for.
std::size_t study_finished(const SweepPlan& header, const std::filesystem::path& dir);

// The study in `dir` as it stands, nothing asked or trained: its trials as a
// plan, their outcomes and the findings (`cnclab sweep merge`, the merge job
// of a Slurm array). `finished` as in run_model_search.
ModelSearch read_study(const SweepPlan& header, const std::filesystem::path& dir);

// ConfigError (exit 2) naming the option when Optuna would refuse the
// sampler, pruner or space of a model-based `spec` (plan_sweep's `header`);
// nothing is written. (run_model_search checks them itself; this is for a
// submission that only plans workers, `sweep --slurm`.)
void check_study_settings(const SweepPlan& header, const SweepSpec& spec);

// Runs the study of `header` (plan_sweep of a model-based `spec`) in `dir`
// until it has spec.trials complete or pruned trials: checks the settings
// (check_study_settings), then stores the plan (store_plan; ConfigError when
// `dir` holds another sweep) and opens the study. One line per finished
// point to `note` (nullptr: silent). ConfigError (exit 2) when Optuna is
// missing (naming python3-optuna), refuses a setting or the sampled space
// makes a bad config; Error when the helper fails.
ModelSearch run_model_search(const SweepPlan& header, const SweepSpec& spec,
                             const SearchSource& source, const std::filesystem::path& dir,
                             const SweepExecuteOptions& options, std::ostream* note);

}  // namespace cnclab
