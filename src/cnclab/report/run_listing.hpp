#pragma once
// `cnclab runs`: one row per result below some folders (run_index.hpp),
// filtered (--where KEY OP VALUE), sorted (--sort KEY, "-KEY" descending)
// and shown as a table, Markdown, CSV or JSON.
//
// A KEY is a run field (file, experiment, kind, status, profile, host,
// start_utc, wall_seconds, cpu_seconds, project_commit, project_dirty,
// config_hash), a metric name (as stored, e.g. test.rmse) or a config key
// (dotted, e.g. dataset.options.keep), or the unique dotted ending of one of
// them ("keep" for dataset.options.keep). OP is one of = != < <= > >= ~
// (~: the text contains VALUE). Both sides numbers: compared as numbers;
// otherwise as text. A run without the key fails every condition on it.
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/report/run_index.hpp"

namespace cnclab {

struct RunCondition {
  std::string key;  // as given
  std::string op;   // = != < <= > >= ~
  std::string value;
};
// "KEY OP VALUE" with or without spaces around OP ("==" is "="). ConfigError
// naming the text otherwise.
RunCondition parse_run_condition(const std::string& text);

struct RunsQuery {
  std::vector<RunCondition> where;   // all must hold
  std::string sort;                  // KEY ascending, -KEY descending; "" file order
  std::vector<std::string> columns;  // empty: status, varying config keys, metrics
  std::string format = "table";      // table | md | csv | json
};

// The text of a run's `key` (resolved: resolve_run_key), nullopt when it has none.
std::optional<std::string> run_value(const IndexedRun& run, const std::string& key);

// `key` as the runs know it: itself when a field, metric or config key of
// some run, else the unique one ending in "." + key. ConfigError naming the
// key (with a suggestion, or the candidates when several end so) otherwise.
std::string resolve_run_key(const std::string& key, const std::vector<IndexedRun>& runs);

// The runs that meet every condition, in the query's order.
std::vector<const IndexedRun*> select_runs(const std::vector<IndexedRun>& runs,
                                           const RunsQuery& query);

// Prints `selected` (from select_runs over `all`, whose varying config keys
// make the default columns).
void print_runs(const std::vector<const IndexedRun*>& selected, const std::vector<IndexedRun>& all,
                const RunsQuery& query, std::ostream& out);

}  // namespace cnclab
