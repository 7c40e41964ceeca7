#pragma once
// `cnclab reproduce --slurm`: the experiment graph as Slurm jobs, submitted
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
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"
#include "cnclab/sweep/slurm_script.hpp"

namespace cnclab {

// Exit 0 when everything needed is submitted (or nothing is needed), 1 when
// a node could not be (its upstream failed to load), 2 for a configuration
// error. Error when sbatch is missing or rejects a script: what was
// submitted before is recorded, nothing after it is submitted.
int reproduce_slurm_command(const std::vector<std::string>& paths, const CommandOptions& options,
                            const SlurmOptions& slurm, std::ostream& out, std::ostream& log);

// `cnclab status RESULTS` for a results folder with a reproduce --slurm
// record: each recorded job, its state (squeue) and whether its output exists.
int reproduce_status_command(const std::filesystem::path& results_dir, std::ostream& out);

}  // namespace cnclab
