#pragma once
// `cnclab gc`: results and datasets that no experiment under the given
// folders still produces, with their sizes; removed only on --yes.
//
// What is current (kept), conservatively:
//   - a result whose config hash equals the resolved config of an experiment
//     file (training or `kind:` job), loaded without a profile and with each
//     profile named by a folder of the results root, recorded by a result or
//     declared at the top of an experiment file (a profile a file does not
//     define leaves it unchanged, so extra names only keep more);
//   - a sweep folder (one holding sweep.yaml) whose plan's experiment is the
//     name of a current experiment, or that a current result names;
//   - what a current result names: its upstream results, its outputs (files
//     beside it), its dataset, and again what those name;
//   - a dataset a current training experiment would read from the cache.
// Stale: the other cnclab results (root attribute format cnclab-result),
// their outputs and sweep folders, and dataset cache files (format
// cnclab-dataset), and the NARX stage cache folder <datasets>/narx-stages
// (a cache: removing it costs only training time). Anything else (foreign
// files, unreadable .h5, READMEs, the runs index, which gc refreshes as
// `cnclab runs` does) is never removed. An experiment file that does not
// load stops gc (exit 2): what it produces cannot be told.
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace cnclab {

struct GcOptions {
  std::vector<std::filesystem::path> experiments;  // experiment files (found by the caller)
  std::filesystem::path results_dir = "results";   // the results root
  std::filesystem::path datasets_dir = "datasets";
  bool remove = false;  // --yes: remove what is stale (else list only)
};

struct GcItem {
  std::filesystem::path path;  // a file or a sweep folder
  std::uintmax_t bytes = 0;
  std::string what;  // "result", "job output", "sweep folder", "dataset", "stage cache"
};

struct GcPlan {
  std::vector<GcItem> stale;
  std::size_t kept = 0;     // current results, sweep folders, outputs and datasets
  std::size_t foreign = 0;  // files gc does not judge
};

GcPlan plan_gc(const GcOptions& options);

// Prints the plan (sizes, total); removes on options.remove. Exit 0.
int gc_command(const GcOptions& options, std::ostream& out);

}  // namespace cnclab
