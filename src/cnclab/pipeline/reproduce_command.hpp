#pragma once
// `cnclab reproduce`: the experiment graph run (reproduce_run.hpp), its
// summary and the tables of the studies whose files ran.
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/experiment/command_options.hpp"

namespace cnclab {

// Runs the experiments under `paths` and the ones they need, upstream first
// (experiment_graph.hpp); reuses every result whose resolved config and
// upstream results are unchanged; prints per experiment ran/reused and why,
// then the tables of the studies whose files ran (with options.check their
// targets). Exit 0, 1 when a run or target failed, 2 for a configuration
// error, 128 + N when interrupted by signal N.
int reproduce_command(const std::vector<std::string>& paths, const CommandOptions& options,
                      std::ostream& out, std::ostream& log);

}  // namespace cnclab
