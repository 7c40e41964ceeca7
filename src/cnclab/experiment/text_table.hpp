#pragma once
// A table of text cells rendered for a terminal (aligned columns), as
// Markdown or as CSV (RFC 4180 quoting). Shared by `sweep`, `compare` and
// `tables`.
#include <ostream>
#include <string>
#include <vector>

namespace cnclab {

struct TextTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;  // each as long as header

  void print_aligned(std::ostream& out) const;
  void print_markdown(std::ostream& out) const;
  void print_csv(std::ostream& out) const;
};

// Numbers for paper tables: %.*g with `digits` significant digits; NaN as "-".
std::string table_number(double value, int digits = 4);

}  // namespace cnclab
