#pragma once
// A plain-text table with aligned columns: a header, a rule, the rows. Same
// shape as the sweep/compare tables' TextTable on the issue-4 branch (fold
// into one when both are on main).
#include <ostream>
#include <string>
#include <vector>

namespace cnclab {

struct TextTable {
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  void print_aligned(std::ostream& out) const;
};

// Numbers for tables: %.*g with `digits` significant digits; NaN as "-".
std::string table_number(double value, int digits = 4);

}  // namespace cnclab
