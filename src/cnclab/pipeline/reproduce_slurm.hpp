#pragma once
// `cnclab reproduce --slurm`'s submission: the experiment graph as Slurm jobs, submitted
// eagerly (returns once everything is queued; nothing of ours keeps running).
//
// - A training experiment whose result is current (the local run's rule,
//   current_result in experiment_graph.hpp) and whose upstream are all
//   current is reused: no job, and dependents do not wait for it.
// - Any other experiment is one job running `cnclab run FILE`, submitted
//   with --dependency=afterok:<its upstream's jobs> (the graph's needs: and
//   init_from:). An experiment whose upstream is submitted is submitted too:
//   whether it is current can only be known once its upstream has run.
// - `kind: sweep` jobs are their trial arrays as `cnclab sweep --slurm`
//   submits them (only trials neither done nor in flight), and a final job
//   after the array running `cnclab run SWEEP_FILE` (the summary and the
//   selection result); a sweep whose trials are all done and whose selection
//   result exists is reused. Other `kind:` jobs are one job each running
//   `cnclab run FILE` (the job decides itself whether its output is current).
//   Jobs run after the graph, as locally: they wait (afterany) for every
//   training job of the graph.
// - A rerun does not submit again what is queued or running: the job ids are
//   recorded in <results>/reproduce-slurm/jobs.yaml (slurm_reproduce_record.hpp).
#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/pipeline/reproduce_inputs.hpp"
#include "cnclab/sweep/slurm_script.hpp"

namespace cnclab {

// One line of the summary: what became of an experiment or job file.
struct ReproduceSlurmRow {
  std::string name;
  std::string action;  // submitted (submit: a dry run), reused, in flight, skipped, ERROR, ...
  std::string job;     // its job id ("{name}" in a dry run); "" when none
  std::string after;   // the job ids it waits for, "a,b" (or "array N" for a sweep's final job)
  std::string why;
};

struct ReproduceSlurmRun {
  std::vector<ReproduceSlurmRow> rows;  // the graph in graph order, then the jobs
  std::size_t submitted = 0;            // jobs sbatch accepted (0 in a dry run)
  int exit_code = 0;                    // 0, 1 (upstream failed to load) or 2 (configuration)
};

// Submits the graph of `inputs.files` and then the jobs, as the rules above
// say (a dry run prints each script and its sbatch line to `out` instead).
// Error when squeue fails (not in a dry run) or sbatch rejects a script: what
// was submitted before is recorded, nothing after it is submitted.
ReproduceSlurmRun submit_reproduce_slurm(const ReproduceInputs& inputs,
                                         const CommandOptions& options, const SlurmOptions& slurm,
                                         std::ostream& out, std::ostream& log);

}  // namespace cnclab
