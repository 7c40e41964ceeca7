#pragma once
// `cnclab report (STUDY | SWEEP_DIR | RESULT ...) -o FILE.html`: one
// self-contained HTML file (html_page.hpp: one style, no script, inline SVG)
// to share from a machine without network:
//   STUDY (a `cnclab tables` name): its tables beside the paper's numbers
//     (the Markdown rendering of `tables`), its declared targets with
//     PASS/FAIL, its figures (study_figures.hpp), and for each result
//     file a table read: provenance, metrics and training history;
//   SWEEP_DIR: the ranking (best first), parallel coordinates of the swept
//     keys and the objective, the parameter importance its summary.h5
//     records (parameter_importance.hpp), and the best trial's run;
//   RESULT: its provenance, metrics and training history.
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include "cnclab/report/tables.hpp"

namespace cnclab {

struct ReportOptions {
  std::vector<std::string> inputs;  // study names, sweep folders, result files
  std::filesystem::path output;     // the .html file (written atomically)
  TablesOptions tables;             // where studies find results, references, manifests
};

struct Report {
  std::string html;
  std::size_t failed_targets = 0;  // declared targets that FAIL
};
// The page; ConfigError for an input that is none of the three.
Report build_report(const ReportOptions& options);

// Writes options.output; prints its path and size. Exit 0 (1 when a
// declared target fails, as `tables --check`).
int report_command(const ReportOptions& options, std::ostream& out);

}  // namespace cnclab
