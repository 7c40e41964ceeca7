#pragma once
// A table of text cells rendered for a terminal (aligned columns), as
// Markdown, as CSV (RFC 4180 quoting), as a LaTeX tabular or as a JSON
// record. Shared by `sweep`, `compare` and `tables` (whose paper tables carry
// numbers as well: typed_table.hpp).
#include <ostream>
#include <string>
#include <vector>

namespace cnclab {

// How `cnclab tables --format` renders: text (aligned columns, the default),
// md, latex (for people); csv, json (numbers only, typed_table.hpp).
enum class TableFormat { text, markdown, csv, latex, json };

// "text", "md", "csv", "latex" or "json"; anything else is a ConfigError
// naming the value and the choices.
TableFormat parse_table_format(const std::string& name);

// The cell of a value a row does not have (a key one run lacks).
inline const std::string kMissingCell = "—";

struct TextTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // each as long as header

  void print_aligned(std::ostream& out) const;
  void print_markdown(std::ostream& out) const;
  void print_csv(std::ostream& out) const;
  // \begin{tabular}{l...} with \hline rules; cells escaped (latex_escape).
  void print_latex(std::ostream& out) const;
  // One line {"table": {"columns": [{"name", "header", "label": true}], "rows":
  // [{header: text}]}}: every cell a string (paper tables: typed_table.hpp).
  void print_json(std::ostream& out) const;
  void print(std::ostream& out, TableFormat format) const;
};

// Text outside the tables (titles, notes) in each format's own syntax, so a
// document of several tables stays valid: a Markdown heading / list item, a
// CSV comment line ("# ..."; CSV readers skip them with comment='#'), a
// LaTeX comment ("% ..."), plain text, or a JSON record line ({"title": ...},
// {"notes": [...]}; print_json_document, tables.hpp, assembles the records).
void print_table_title(std::ostream& out, TableFormat format, const std::string& title);
void print_table_notes(std::ostream& out, TableFormat format,
                       const std::vector<std::string>& notes);

// The ten LaTeX special characters escaped (& % $ # _ { } ~ ^ and backslash); UTF-8 kept.
std::string latex_escape(const std::string& text);

// Numbers for paper tables: %.*g with `digits` significant digits; NaN as "-".
std::string table_number(double value, int digits = 4);

}  // namespace cnclab
