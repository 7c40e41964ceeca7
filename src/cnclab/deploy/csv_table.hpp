#pragma once
// Tables of named numeric columns as CSV, what `cnclab predict` reads (raw
// inputs) and writes (predictions):
//   # comment lines           skipped on reading; provenance on writing
//   name [unit],name,...      header: each column's name, its unit in
//                             brackets (optional on reading)
//   1.5,-2e-3,...             one row per sample, numbers as strtod reads them
// No quoting: names hold no comma. Numbers are written in their shortest
// text that reads back exactly (core/format.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "cnclab/deploy/named_column.hpp"

namespace cnclab {

// The columns, with unit "" where the header gives none. ConfigError naming
// the file, line and column: no header, an empty or repeated column name, a
// row of another width, a cell that is not a number, NaN or infinity, no row
// at all.
std::vector<NamedColumn> read_csv_table(const std::filesystem::path& file);

// The CSV text of `columns` (equal lengths) after `comments` (each one line,
// written as "# " + line); a unit "" is left out of the header.
std::string csv_text(const std::vector<std::string>& comments,
                     const std::vector<NamedColumn>& columns);

}  // namespace cnclab
