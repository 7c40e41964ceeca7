#pragma once
// Experiments and the experiments whose results they need (`needs:`,
// `init_from:`) as a graph, in dependency order, and the rule that decides
// whether an existing result can be reused.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/experiment/result_store.hpp"
#include "cnclab/experiment/run_record.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {

struct GraphNode {
  std::filesystem::path file;
  std::optional<LoadedExperiment> experiment;  // empty when loading failed
  std::string load_error;                      // why (a ConfigError's text)
  bool config_error = false;                   // load_error is a configuration error
  std::vector<std::size_t> upstream;           // indices of the nodes it needs (earlier)
  bool requested = true;                       // false: added only as someone's upstream
};

// Loads `files` and, transitively, every experiment they need; returns them
// upstream first (otherwise in the order given). A file that fails to load is
// a node with load_error. ConfigError naming the files on a dependency cycle.
std::vector<GraphNode> load_graph(const std::vector<std::filesystem::path>& files,
                                  const std::string& profile = {});

struct CurrentUpstream {
  std::string name;      // upstream experiment name, for messages
  std::string identity;  // result_identity of its current result
};

// Why a result made from the upstream results `recorded` (its /upstream) is
// out of date given the upstream results now, or "" when it is current. The
// result path itself encodes the resolved config (its hash), so an existing
// file at that path already has an unchanged config.
std::string staleness(const std::vector<UpstreamRef>& recorded,
                      const std::vector<CurrentUpstream>& upstream);

// The reuse rule of `cnclab reproduce` (local and --slurm): the stored
// result of `experiment` (store.existing for its resolved config) when it is
// current given its upstream results now, else why it must run: no result,
// upstream changed (staleness), the dataset generator changed (the dataset
// file name carries the generator version, which the resolved config does
// not), or the result is unreadable.
struct CurrentResult {
  std::optional<RunRecord> record;  // set when current
  std::string why;                  // why it must run, when not
};
CurrentResult current_result(const LoadedExperiment& experiment,
                             const std::vector<CurrentUpstream>& upstream,
                             const ResultStore& store);

}  // namespace cnclab
