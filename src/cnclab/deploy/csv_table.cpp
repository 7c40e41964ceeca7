#include "cnclab/deploy/csv_table.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "cnclab/core/error.hpp"
#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {

std::vector<std::string> split_cells(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = line.find(',', start);
    cells.push_back(line.substr(start, comma - start));
    if (comma == std::string::npos) return cells;
    start = comma + 1;
  }
}

std::string trimmed(const std::string& s) {
  const auto first = s.find_first_not_of(" \t\r");
  if (first == std::string::npos) return "";
  return s.substr(first, s.find_last_not_of(" \t\r") - first + 1);
}

// "name [unit]" -> name and unit.
NamedColumn header_cell(const std::string& cell, const std::string& where) {
  NamedColumn c;
  const std::string text = trimmed(cell);
  const auto open = text.find('[');
  if (open != std::string::npos) {
    if (text.back() != ']') throw ConfigError(where + ": '" + text + "': a unit ends with ']'");
    c.unit = trimmed(text.substr(open + 1, text.size() - open - 2));
    if (c.unit.empty()) throw ConfigError(where + ": '" + text + "': an empty unit");
    c.name = trimmed(text.substr(0, open));
  } else {
    c.name = text;
  }
  if (c.name.empty()) throw ConfigError(where + ": a column without a name");
  return c;
}

double number_cell(const std::string& cell, const std::string& where) {
  const std::string text = trimmed(cell);
  char* end = nullptr;
  errno = 0;
  const double x = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size()) {
    throw ConfigError(where + ": '" + text + "' is not a number");
  }
  if (!std::isfinite(x)) throw ConfigError(where + ": " + text + " (NaN or infinity)");
  return x;
}

}  // namespace

std::vector<NamedColumn> read_csv_table(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw ConfigError(file.string() + ": cannot open");
  std::vector<NamedColumn> columns;
  std::vector<std::vector<double>> values;
  std::string line;
  std::size_t line_no = 0;
  bool header = false;
  while (std::getline(in, line)) {
    ++line_no;
    const std::string text = trimmed(line);
    if (text.empty() || text[0] == '#') continue;
    const std::string where = file.string() + ":" + std::to_string(line_no);
    const auto cells = split_cells(text);
    if (!header) {
      for (std::size_t j = 0; j < cells.size(); ++j) {
        columns.push_back(header_cell(cells[j], where + " column " + std::to_string(j + 1)));
        for (std::size_t k = 0; k < j; ++k) {
          if (columns[k].name == columns[j].name) {
            throw ConfigError(where + ": column '" + columns[j].name + "' appears twice");
          }
        }
      }
      values.resize(columns.size());
      header = true;
      continue;
    }
    if (cells.size() != columns.size()) {
      throw ConfigError(where + ": " + std::to_string(cells.size()) + " values, the header names " +
                        std::to_string(columns.size()) + " columns");
    }
    for (std::size_t j = 0; j < cells.size(); ++j) {
      values[j].push_back(number_cell(
          cells[j], where + " column " + std::to_string(j + 1) + " (" + columns[j].name + ")"));
    }
  }
  if (!header) throw ConfigError(file.string() + ": empty (no header line naming the columns)");
  if (values.empty() || values[0].empty()) {
    throw ConfigError(file.string() + ": no rows of values after the header");
  }
  for (std::size_t j = 0; j < columns.size(); ++j) {
    columns[j].values = Eigen::Map<const Eigen::VectorXd>(
        values[j].data(), static_cast<Eigen::Index>(values[j].size()));
  }
  return columns;
}

std::string csv_text(const std::vector<std::string>& comments,
                     const std::vector<NamedColumn>& columns) {
  std::ostringstream out;
  for (const auto& c : comments) out << "# " << c << "\n";
  for (std::size_t j = 0; j < columns.size(); ++j) {
    out << (j ? "," : "") << columns[j].name;
    if (!columns[j].unit.empty()) out << " [" << columns[j].unit << "]";
  }
  out << "\n";
  const Eigen::Index rows = columns.empty() ? 0 : columns[0].values.size();
  for (Eigen::Index i = 0; i < rows; ++i) {
    for (std::size_t j = 0; j < columns.size(); ++j) {
      out << (j ? "," : "") << shortest_double(columns[j].values[i]);
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace cnclab
