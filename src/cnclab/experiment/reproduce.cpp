// `cnclab reproduce`: the experiment graph, upstream first, reusing current
// results (DVC-style stage caching; see experiment_graph.hpp).
#include <iomanip>
#include <optional>

#include "cnclab/core/error.hpp"
#include "cnclab/experiment/commands.hpp"
#include "cnclab/experiment/dataset_cache.hpp"
#include "cnclab/experiment/experiment_graph.hpp"
#include "cnclab/experiment/job_kinds.hpp"
#include "cnclab/experiment/result_file.hpp"
#include "cnclab/experiment/runner.hpp"
#include "cnclab/experiment/tables/tables.hpp"
#include "cnclab/experiment/upstream.hpp"

namespace cnclab {
namespace fs = std::filesystem;
namespace {

struct Row {
  std::string name, action, why, detail, file;
};

// The result this experiment has now, or why it has none.
struct NodeState {
  std::optional<RunRecord> record;
  std::string problem;  // non-empty: no usable result
};

}  // namespace

int reproduce_command(const std::vector<std::string>& paths, const CommandOptions& options,
                      std::ostream& out, std::ostream& log) {
  const auto found = find_experiments(paths);
  if (found.empty()) throw ConfigError("reproduce: no experiment files found");
  // `kind: <job>` files (job_kinds.hpp) take no part in the training graph
  // and run after it; a file whose kind cannot be read stays in the graph, to
  // be reported there.
  std::vector<fs::path> files;
  std::vector<std::pair<fs::path, JobKind>> jobs;
  for (const auto& file : found) {
    std::optional<JobKind> kind;
    try {
      kind = find_job_kind(experiment_kind(file));
    } catch (const ConfigError&) {
    }
    if (kind) {
      jobs.emplace_back(file, std::move(*kind));
    } else {
      files.push_back(file);
    }
  }
  const std::vector<GraphNode> graph = load_graph(files, options.profile);
  std::vector<NodeState> state(graph.size());
  std::vector<Row> rows;
  int exit_code = 0;
  for (std::size_t i = 0; i < graph.size(); ++i) {
    const GraphNode& node = graph[i];
    if (!options.quiet) {
      log << "[" << i + 1 << "/" << graph.size() << "] " << node.file.string() << "\n";
    }
    if (!node.experiment) {
      rows.push_back({node.file.string(), node.config_error ? "CONFIG ERROR" : "ERROR",
                      node.load_error, "", ""});
      state[i].problem = "failed to load";
      exit_code = node.config_error ? 2 : std::max(exit_code, 1);
      continue;
    }
    const LoadedExperiment& exp = *node.experiment;
    // Experiments not asked for, added because others need them, say so.
    const std::string name = exp.spec.name + (node.requested ? "" : " (upstream)");
    std::vector<CurrentUpstream> upstream;
    std::string blocked;
    for (std::size_t j : node.upstream) {
      const std::string up_name =
          graph[j].experiment ? graph[j].experiment->spec.name : graph[j].file.string();
      if (!state[j].record) {
        blocked = "upstream " + up_name + " has no result (" + state[j].problem + ")";
        break;
      }
      upstream.push_back({up_name, result_identity(*state[j].record)});
    }
    if (!blocked.empty()) {
      rows.push_back({name, "skipped", blocked, "", ""});
      state[i].problem = "skipped";
      exit_code = std::max(exit_code, 1);
      continue;
    }

    const fs::path path = result_path(exp, options.results_dir);
    std::string why;
    std::error_code ec;
    if (options.force) {
      why = "--force";
    } else if (!fs::exists(path, ec)) {
      why = "no result for this resolved config yet";
    } else {
      try {
        RunRecord existing = read_result(path);
        why = staleness(existing.upstream, upstream);
        // The dataset file name carries the generator version (not part of
        // the resolved config): a new generator version makes a new dataset.
        const fs::path dataset = dataset_cache_file(exp.spec.dataset, generator_seed(exp.spec), "");
        if (why.empty() && fs::path(existing.dataset_file).filename() != dataset.filename()) {
          why = "dataset generator changed (" + dataset.filename().string() + ")";
        }
        if (why.empty()) state[i].record = std::move(existing);
      } catch (const IoError& e) {
        why = std::string("result unreadable (") + e.what() + ")";
      }
    }
    try {
      std::string action = "reused";
      if (why.empty()) {
        why = "config and upstream results unchanged";
      } else {
        action = "ran";
        run_experiment(exp, run_options(options, log));
        state[i].record = read_result(path);
      }
      const RunRecord& r = *state[i].record;
      const bool ok = r.provenance.status == "complete";
      rows.push_back({name, ok ? action : action + ", FAILED", why,
                      ok ? metrics_line(r.metrics) : r.provenance.failure_reason, path.string()});
      if (!ok) exit_code = std::max(exit_code, 1);
    } catch (const ConfigError& e) {
      rows.push_back({name, "CONFIG ERROR", why, e.what(), ""});
      state[i].problem = "configuration error";
      exit_code = 2;
    } catch (const Error& e) {
      rows.push_back({name, "ERROR", why, e.what(), ""});
      state[i].problem = "error";
      exit_code = std::max(exit_code, 1);
    }
  }
  // Jobs read training results: they run after the graph, in file order.
  std::string reports;
  const JobContext context{options, {}, options.quiet ? nullptr : &log};
  for (const auto& [file, kind] : jobs) {
    if (!options.quiet) log << "[" << kind.kind << "] " << file.string() << "\n";
    try {
      const JobReport r = kind.run(file, context);
      rows.push_back({r.name, r.action, r.why, r.detail, r.file});
      if (!r.report.empty()) reports += "\n" + r.report;
    } catch (const ConfigError& e) {
      rows.push_back({file.string(), "CONFIG ERROR", kind.kind + " job", e.what(), ""});
      exit_code = 2;
    } catch (const Error& e) {
      rows.push_back({file.string(), "ERROR", kind.kind + " job", e.what(), ""});
      exit_code = std::max(exit_code, 1);
    }
  }
  out << "\n== cnclab reproduce: " << rows.size() << " experiment(s) ==\n";
  for (const auto& row : rows) {
    out << std::left << std::setw(28) << row.name << " " << std::setw(12) << row.action << " "
        << row.why << "\n";
    if (!row.detail.empty()) out << std::string(30, ' ') << row.detail << "\n";
    if (!row.file.empty()) out << std::string(30, ' ') << row.file << "\n";
  }
  out << reports;
  TablesOptions tables;
  tables.results_dir = options.results_dir;
  tables.profile = options.profile;
  print_available_tables(tables, out);
  return exit_code;
}

}  // namespace cnclab
