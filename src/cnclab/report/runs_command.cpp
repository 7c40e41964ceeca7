#include "cnclab/report/runs_command.hpp"

#include <algorithm>

#include "cnclab/core/error.hpp"
#include "cnclab/report/compare.hpp"
#include "cnclab/report/run_index.hpp"
#include "cnclab/report/run_listing.hpp"

namespace cnclab {
namespace fs = std::filesystem;

int runs_command(const RunsOptions& o, std::ostream& out, std::ostream& err) {
  if (o.format != "table" && o.format != "md" && o.format != "csv" && o.format != "json") {
    throw ConfigError("--format " + o.format + ": must be one of: table, md, csv, json");
  }
  if (!o.diff.empty()) {
    if (o.diff.size() != 2) throw ConfigError("--diff: needs two result files (A B)");
    print_comparison(collect_runs(o.diff), parse_compare_format(o.format), out, o.full);
    return 0;
  }
  RunsQuery q;
  q.format = o.format;
  q.sort = o.sort;
  for (const auto& words : o.where) {
    std::string text;
    for (const auto& w : words) text += (text.empty() ? "" : " ") + w;
    q.where.push_back(parse_run_condition(text));
  }
  for (const auto& c : o.columns) {
    std::size_t begin = 0;
    while (begin <= c.size()) {
      const auto end = std::min(c.find(',', begin), c.size());
      if (end > begin) q.columns.push_back(c.substr(begin, end - begin));
      begin = end + 1;
    }
  }
  std::vector<fs::path> inputs(o.folders.begin(), o.folders.end());
  if (inputs.empty()) {
    std::error_code ec;
    if (!fs::is_directory(o.results_dir, ec)) {
      throw ConfigError(o.results_dir.string() +
                        ": no results folder (run an experiment first, or name folders)");
    }
    inputs.push_back(o.results_dir);
  }
  const RunScan scan = scan_runs(inputs, o.no_index ? fs::path() : runs_index_path(o.results_dir));
  if (!scan.index_note.empty()) err << "note: " << scan.index_note << "\n";
  if (!scan.unreadable.empty()) {
    err << "note: " << scan.unreadable.size() << " .h5 file"
        << (scan.unreadable.size() == 1 ? " is" : "s are") << " not a readable result, e.g. "
        << scan.unreadable.front().error << "\n";
  }
  print_runs(select_runs(scan.runs, q), scan.runs, q, out);
  return 0;
}

}  // namespace cnclab
