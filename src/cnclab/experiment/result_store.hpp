#pragma once
// One answer to "the result of experiment X under profile P in results
// folder R", for everything that reads results: upstream results (needs,
// init_from), `reproduce`'s reuse, the paper tables and the job kinds.
//
// Rules:
// - Identity: a result is named by what made it, the hash of its resolved
//   configuration: R/<name>/<name>[-seed<seed>]-<first 8 hex digits>.h5
//   (path_of), and the file's own config_hash must equal the full hash. A
//   result of another configuration is never taken, however recent.
// - Current only: a training result of an older result format (its metrics
//   are not per split; result_file.hpp) is not reused: `get` says there is
//   none, `reproduce` and sweeps make it again.
// - Complete only: a file that is not a complete result (no `complete`
//   attribute, partial name, unreadable) is not a result; `get` then says
//   there is none. A complete run whose training failed is returned only
//   when the caller accepts failed runs (Accept::complete_or_failed).
// - None: MissingResults naming the experiment file, the expected file and
//   the command that makes it (`cnclab run FILE --profile P`, or `cnclab
//   reproduce FILE ...` when it needs other results first). Never a fallback
//   to another file.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/run_record.hpp"
#include "cnclab/experiment/spec.hpp"

namespace cnclab {

// The result asked for does not exist (yet) or is not a complete result.
class MissingResults : public IoError {
 public:
  using IoError::IoError;
};

// A readable result of the config asked for, but of an older result format
// that is not reused (the rule "Current only" above).
class OutdatedResult : public IoError {
 public:
  using IoError::IoError;
};

// What identifies a result.
struct ResultKey {
  std::string name;                   // experiment or job name: R/<name>/
  std::optional<std::uint64_t> seed;  // training runs: "-seed<seed>" in the file name
  std::string resolved_yaml;          // the identity: its hash names the file
  std::filesystem::path source_file;  // the experiment or job file (messages, the command)
  bool has_upstream = false;          // making it needs other results (command: reproduce)
};

// A training experiment's key: name, seed, resolved config, upstream files.
ResultKey result_key(const LoadedExperiment& experiment);

// R/<name>/<name>[-seed<seed>]-<first 8 hex digits of hash_hex(resolved_yaml)>.h5
std::filesystem::path result_path(const ResultKey& key, const std::filesystem::path& results_dir);
// result_path(result_key(experiment), results_dir): where `cnclab run` writes.
std::filesystem::path result_path(const LoadedExperiment& experiment,
                                  const std::filesystem::path& results_dir);

enum class Accept { complete, complete_or_failed };

struct StoredResult {
  std::filesystem::path file;
  RunRecord record;
  bool complete() const { return record.provenance.status == "complete"; }
};

class ResultStore {
 public:
  explicit ResultStore(std::filesystem::path results_dir, std::string profile = {});

  const std::filesystem::path& results_dir() const { return results_dir_; }
  const std::string& profile() const { return profile_; }

  std::filesystem::path path_of(const ResultKey& key) const;
  // `cnclab run FILE [--profile P] [--out ROOT]` (reproduce when
  // key.has_upstream); ROOT the root of the store's folder (results_folder:
  // R = ROOT/P), --out only when it is not the default "results".
  std::string make_command(const ResultKey& key) const;

  // The experiment file with the store's profile (load_experiment's errors).
  LoadedExperiment load(const std::filesystem::path& experiment_file) const;

  // The result of `key`: MissingResults when there is none (see above);
  // Error naming the file when it failed and `accept` is complete.
  StoredResult get(const ResultKey& key, Accept accept = Accept::complete) const;
  StoredResult get(const LoadedExperiment& experiment, Accept accept = Accept::complete) const;
  // Loads `experiment_file` with the profile, then get(); MissingResults
  // when the file itself does not exist.
  StoredResult get(const std::filesystem::path& experiment_file,
                   Accept accept = Accept::complete) const;
  // get(file, accept) of each file, in order, the results read with one
  // isolated child for all readable ones (read_results); throws what a
  // failing get() would (an absent experiment file before any result).
  std::vector<StoredResult> get_all(const std::vector<std::filesystem::path>& experiment_files,
                                    Accept accept = Accept::complete) const;

  // What reuse needs: the result at key's path as it stands (failed runs
  // included); nullopt when no file is there; IoError when a file is there
  // but is not a readable complete result of this config.
  std::optional<StoredResult> existing(const ResultKey& key) const;

 private:
  std::string missing_text(const ResultKey& key, const std::string& why) const;
  // The key of an experiment file (MissingResults when the file is absent).
  ResultKey key_of(const std::filesystem::path& experiment_file) const;
  // `r`, read from key's path, when it is a current result of key's config:
  // OutdatedResult or IoError otherwise.
  StoredResult checked(const ResultKey& key, StoredResult r) const;
  // get()'s rules over what `existing` (existing() or a read done before)
  // gives for key.
  StoredResult accepted(const ResultKey& key,
                        const std::function<std::optional<StoredResult>()>& existing,
                        Accept accept) const;
  std::filesystem::path results_dir_;
  std::string profile_;
};

// The one rule for results folders, the same for `run`, `sweep`, `reproduce`
// and `tables`: --out / --results name the root ROOT (default "results") and
// --profile P picks its subfolder ROOT/P; no profile: ROOT itself.
// Folders in the layout before this rule keep working: until then an
// explicit `--out ROOT --profile P` wrote ROOT itself. So when the root was
// given (`root_given`), ROOT/P does not exist and ROOT holds results directly
// (a folder of it with a result file or a sweep folder), ROOT is used as it
// is and `note` says so. The default root never falls back: `reproduce
// --quick` always wrote results/quick.
struct ResultsFolder {
  std::filesystem::path dir;  // where results are read and written
  std::string note;           // empty, or why ROOT itself is used (old layout)
};
ResultsFolder results_folder(const std::filesystem::path& root, const std::string& profile,
                             bool root_given);

// The root ROOT that results_folder turns into `folder` (ROOT/P gives ROOT;
// an old-layout folder, without /P, is its own root): what a command run
// again elsewhere (`cnclab ... --out ROOT --profile P`, a Slurm job) is given.
std::filesystem::path results_root(const std::filesystem::path& folder, const std::string& profile);

// A path for a table's `sources:` footer: relative to the working directory
// when it lies below it, otherwise as given.
std::string source_path_text(const std::filesystem::path& file);

}  // namespace cnclab
