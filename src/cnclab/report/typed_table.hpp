#pragma once
// A paper table whose cells carry their numbers as well as their text, so
// one builder serves people and programs (`cnclab tables --format`):
//   text, md, latex: each cell's `text`, exactly as the builder formatted it
//                    ("5.01 ± 0.83", "5/5", "150+40", "-");
//   csv, json:       each cell's numbers, one column per part, units in the
//                    column names ("contour_rms_mean_um", "contour_rms_std_um";
//                    "stable", "runs"), full precision (shortest_double), a
//                    missing number empty (csv) or null (json).
// A column is a label column (text a program matches on: method, source) or
// a number column of one or more parts (mean and std, count and total).
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "cnclab/report/text_table.hpp"

namespace cnclab {

struct TableColumn {
  std::string header;              // what people read: "contour RMS"
  std::vector<std::string> parts;  // csv/json column names: {"contour_rms_mean_um", ...}
  bool label = false;              // one text part instead of numbers
};

// "method": a label column whose csv/json name is `name`.
TableColumn label_column(std::string header, std::string name);
// One number, named name_unit ("max_abs_um"); no unit: name alone.
TableColumn number_column(std::string header, const std::string& name,
                          const std::string& unit = "");
// Mean and standard deviation: name_mean_unit, name_std_unit.
TableColumn mean_std_column(std::string header, const std::string& name, const std::string& unit);
// Two numbers with names of their own: "5/5" as {"stable", "runs"}, "150+40"
// as {"open_epochs", "closed_epochs"}.
TableColumn pair_column(std::string header, std::string first, std::string second);

// Machine-name form of a display label: lower case, runs of anything but
// letters, digits and '.' as one '_' ("ours, tuned" -> "ours_tuned").
std::string machine_name(const std::string& text);

struct TableCell {
  std::string text;  // shown by text, md and latex
  // A number column's parts (NaN or absent: missing); for a label column
  // the label csv/json carry (when empty, `text`).
  std::vector<double> numbers;
  std::optional<std::string> key;
  // False for a cell made from text alone: allowed in a label column only,
  // so a number column cannot silently print strings (std::logic_error).
  bool typed = false;

  TableCell(std::string shown) : text(std::move(shown)) {}  // NOLINT: text cells read naturally
  TableCell(const char* shown) : text(shown) {}             // NOLINT
};

TableCell number_cell(double value, std::string text);
TableCell mean_std_cell(double mean, double std, std::string text);
TableCell pair_cell(double first, double second, std::string text);
// A number column's cell without a value ("-", "n/a", "diverged", "see note").
TableCell missing_cell(std::string text);
// A label shown as `text` and carried as `key` ("" shown, "max_abs_um" carried
// on a continuation row; "Number" shown, "count" carried).
TableCell label_cell(std::string text, std::string key);

struct TypedTable {
  std::vector<TableColumn> columns;
  std::vector<std::vector<TableCell>> rows;  // each as long as columns

  // The people's table: headers and cell texts.
  TextTable text_table() const;
  // text, md, latex through text_table(); csv and json as above (json: one
  // line {"table": {"columns": [...], "rows": [{name: value}]}}, a record
  // assembled into the document by print_json_document, tables.hpp).
  void print(std::ostream& out, TableFormat format) const;
};

}  // namespace cnclab
