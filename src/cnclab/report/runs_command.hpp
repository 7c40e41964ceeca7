#pragma once
// The body of `cnclab runs` (run_listing.hpp, run_index.hpp).
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

namespace cnclab {

struct RunsOptions {
  std::vector<std::string> folders;  // result files or folders; empty: the results root
  std::filesystem::path results_dir = "results";  // the root: its index file
  // Each --where: "KEY OP VALUE" as one word or as three (joined by spaces).
  std::vector<std::vector<std::string>> where;
  std::string sort;                  // KEY, -KEY descending
  std::vector<std::string> columns;  // --columns a,b,c (split on commas)
  std::string format = "table";      // table | md | csv | json
  std::vector<std::string> diff;     // --diff A B: two result files
  bool no_index = false;             // --no-index: read every file, leave the index alone
  bool full = false;                 // --diff: arrays in full
};

// Exit 0; ConfigError (exit 2) on a bad key, operator, format or path.
// Notes (files that are not results, index trouble) go to `err`.
int runs_command(const RunsOptions& options, std::ostream& out, std::ostream& err);

}  // namespace cnclab
