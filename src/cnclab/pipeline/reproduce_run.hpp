#pragma once
// `cnclab reproduce`: the experiment graph, upstream first, reusing current
// results (DVC-style stage caching; see experiment_graph.hpp). Experiments
// whose upstream results are ready train in parallel, each in its own process
// (trial_pool.hpp, like sweep trials): results are bit-identical to running
// them one by one, since a run depends only on its resolved config. The
// `kind:` jobs run after the graph; their datasets (JobKind::prework) are
// generated into the cache in free slots while the graph trains, under the
// same --jobs budget.
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/pipeline/reproduce_inputs.hpp"

namespace cnclab {

// One line of reproduce's summary: what became of an experiment or job.
struct ReproduceRow {
  std::string name;    // the experiment's name ("NAME (upstream)" when only needed), or file
  std::string action;  // ran, reused, skipped, not run, ERROR, CONFIG ERROR, "ran, FAILED", ...
  std::string why;     // why it ran or did not
  std::string detail;  // its metrics, or the error
  std::string file;    // its result file; "" when none
};

struct ReproduceRun {
  std::vector<ReproduceRow> rows;  // the graph's experiments in graph order, then the jobs'
  std::string reports;             // the jobs' reports, each after a blank line
  int exit_code = 0;               // 0, 1 (a run or job failed) or 2 (a configuration error)
  int stopped = 0;                 // the signal that stopped it, or 0
};

// Trains the graph of `inputs.files` (upstream first, up to options.jobs at
// once, 0: the cores available), reusing current results, with the jobs'
// prework in free slots; then, unless a signal stopped it, runs the jobs in
// file order. Progress goes to `log` unless options.quiet.
ReproduceRun run_reproduce(const ReproduceInputs& inputs, const CommandOptions& options,
                           std::ostream& log);

}  // namespace cnclab
