#pragma once
// A plain-text table with left-aligned columns sized to their widest cell;
// what `cnclab tables` prints.
#include <ostream>
#include <string>
#include <vector>

namespace cnclab {

class TextTable {
 public:
  void add_row(std::vector<std::string> cells) { rows_.push_back(std::move(cells)); }
  // A horizontal rule across all columns.
  void add_rule() { rows_.emplace_back(); }
  void print(std::ostream& out) const;

 private:
  std::vector<std::vector<std::string>> rows_;
};

// Numbers for tables: %.*g with `digits` significant digits.
std::string table_number(double value, int digits = 4);

}  // namespace cnclab
