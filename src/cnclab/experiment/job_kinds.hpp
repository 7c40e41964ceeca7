#pragma once
// Experiment files that are not training runs: `kind: <name>` jobs (G-code,
// timing studies, sweeps, searches...). Each kind is one entry here;
// `cnclab run` and `cnclab validate` dispatch on it, and `cnclab reproduce`
// runs every job after the training graph (so the training results a job
// reads exist by then), in file order; a job's prework (its datasets) runs
// beside the graph. Adding a kind: write its loader and
// runner in its study's folder and register it from the study's register
// function (called by src/cli/builtins.cpp); lower modules never name a kind.
//
// A job decides itself whether its existing output is current (compare a
// hash of its resolved config stored with the output, like
// experiment/experiment_graph.hpp does for training runs) and says so in
// JobReport::action / why.
#include <filesystem>
#include <functional>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/core/field_info.hpp"
#include "cnclab/experiment/command_options.hpp"

namespace cnclab {

// What a job is given: the command's options (results and dataset folders,
// quiet, force, regenerate, profile) and where progress goes.
struct JobContext {
  CommandOptions options;
  std::vector<std::string> overrides;  // `key=value` (run / validate only; empty in reproduce)
  std::ostream* log = nullptr;         // progress and notes; null when quiet
};

// One line of `reproduce`'s summary, plus an optional report printed after it.
struct JobReport {
  std::string name;    // the job's `name:`
  std::string action;  // "ran", "reused", ...
  std::string why;     // why it ran or was reused
  std::string detail;  // one line of figures
  std::string file;    // main output file
  std::string report;  // printed after the summary (may be empty)
};

// Work a job needs done before it runs that does not depend on training
// results, such as generating its datasets into the cache: `reproduce` runs
// it in a free slot while the training graph runs. Equal keys are the same
// work (done once).
struct JobPrework {
  std::string key;   // e.g. the dataset cache file
  std::string what;  // for the log: "dataset following_error-….h5"
  std::function<void()> run;
};

struct JobKind {
  std::string kind;  // the value of `kind:`
  std::string summary;
  // Loads the file (strictly, with the context's profile and overrides),
  // runs the job and writes its outputs atomically. ConfigError for bad
  // configuration, Error for a failed run.
  std::function<JobReport(const std::filesystem::path& file, const JobContext& context)> run;
  // The resolved configuration as YAML (`cnclab validate`); throws like run.
  std::function<std::string(const std::filesystem::path& file, const JobContext& context)>
      resolved_yaml;
  // The JSON Schema of the kind's files (`cnclab schema`; experiment_schema.hpp),
  // from its field declarations. Empty while its keys are not declared: the
  // schema then says so and accepts any keys.
  std::function<nlohmann::json()> schema = {};
  // The job's prework (see JobPrework) that is not done yet; empty: none.
  // Throws like run (reproduce then leaves the error to the job's own run).
  std::function<std::vector<JobPrework>(const std::filesystem::path& file,
                                        const JobContext& context)>
      prework = {};
  // The training experiment files whose results the job reads (the feedrate
  // job's `predictor:`), loaded with `profile`: `reproduce` adds them to its
  // training graph, as `needs:` does for an experiment, so that reproducing
  // the job alone makes them first. Empty function: none. Throws like run
  // (reproduce then leaves the error to the job's own run).
  std::function<std::vector<std::filesystem::path>(const std::filesystem::path& file,
                                                   const std::string& profile)>
      upstream = {};
  // The other files whose `profiles:` the job's --profile reaches (a `kind:
  // sweep` file's experiment, whose trials load with the profile), for the
  // profile check (profiles.hpp). Empty function: the file's own only.
  std::function<std::vector<std::filesystem::path>(const std::filesystem::path& file)>
      profile_sources = {};
};

// A kind whose files load into a `Job` by `load(file, overrides, profile)`
// (strict, as JobKind::run asks) and resolve by `to_yaml(job)`; `run(job,
// context)` runs a loaded job and returns its report.
template <class Load, class Run>
JobKind job_kind(std::string kind, std::string summary, Load load, Run run) {
  JobKind k;
  k.kind = std::move(kind);
  k.summary = std::move(summary);
  k.run = [load, run](const std::filesystem::path& file, const JobContext& c) {
    return run(load(file, c.overrides, c.options.profile), c);
  };
  k.resolved_yaml = [load](const std::filesystem::path& file, const JobContext& c) {
    return to_yaml(load(file, c.overrides, c.options.profile));
  };
  return k;
}

// Registers a kind (src/cli/builtins.cpp, before any command runs).
// std::logic_error for "train" or a kind registered twice.
void register_job_kind(JobKind kind);
// The registered kinds, in registration order.
const std::vector<JobKind>& registered_job_kinds();

// The keys a job file starts with, for its kind's schema: `kind` (this one,
// required), `name` and `description` as a training experiment declares them.
std::vector<FieldInfo> job_file_fields(const std::string& kind);

// The `kind:` of an experiment file: "train" (absent key) or a job kind.
// ConfigError for unreadable YAML or an unknown kind, listing the known ones.
std::string experiment_kind(const std::filesystem::path& file);

// The job kind named `kind`, or nullopt for "train".
std::optional<JobKind> find_job_kind(const std::string& kind);

}  // namespace cnclab
