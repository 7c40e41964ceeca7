#pragma once
// A sweep's parameter importance, when its summary.h5 records one (an Optuna
// sweep's evaluator, e.g. fANOVA):
//   /importance              group; attribute evaluator ("fanova")
//   /importance/parameter    1-D strings, the swept keys
//   /importance/value        1-D float64, the same length, each key's share
//                            of the objective's variance (sorted descending)
// Shown by `cnclab report` as a bar chart and a table.
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/report/html_page.hpp"

namespace cnclab {

struct ParameterImportance {
  std::string evaluator;                               // "" when not recorded
  std::vector<std::pair<std::string, double>> values;  // largest first
};

// nullopt when the file has no /importance group; IoError naming the file
// and object when it has one that does not follow the layout above
// (lengths differ, a value not finite or negative).
std::optional<ParameterImportance> read_parameter_importance(
    const std::filesystem::path& summary_file);

// An inline <svg> horizontal bar chart (role="img"): one bar per parameter,
// longest first, its value at the bar's end.
std::string svg_bar_chart(const std::vector<std::pair<std::string, double>>& bars,
                          const std::string& title, const std::string& value_label);

// The chart and a table (parameter, importance) on the page, or a note
// naming the problem when the group is malformed; nothing when absent.
void add_parameter_importance(HtmlPage& page, const std::filesystem::path& summary_file);

}  // namespace cnclab
