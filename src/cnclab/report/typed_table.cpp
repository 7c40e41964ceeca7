#include "cnclab/report/typed_table.hpp"

#include <cctype>
#include <cmath>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>
#include <utility>
#include <variant>

#include "cnclab/core/format.hpp"

namespace cnclab {
namespace {

std::string typed_with_unit(const std::string& name, const std::string& unit) {
  return unit.empty() ? name : name + "_" + unit;
}

std::string typed_csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// The value of part `k` of `cell` in column `c`: a label's text, a number, or
// nullopt (missing). A text-only cell in a number column is a builder's bug.
using TypedPart = std::optional<std::variant<std::string, double>>;
TypedPart typed_part(const TableColumn& c, const TableCell& cell, std::size_t k) {
  if (c.label) return cell.key ? *cell.key : cell.text;
  if (!cell.typed) {
    throw std::logic_error("table column '" + c.header + "': cell '" + cell.text +
                           "' has no number (make it with number_cell or missing_cell)");
  }
  if (k >= cell.numbers.size() || std::isnan(cell.numbers[k])) return std::nullopt;
  return cell.numbers[k];
}

void typed_check(const TypedTable& t) {
  std::set<std::string> names;
  for (const auto& c : t.columns) {
    for (const auto& p : c.parts) {
      if (!names.insert(p).second) {
        throw std::logic_error("table column name '" + p + "' appears twice");
      }
    }
  }
  for (const auto& row : t.rows) {
    if (row.size() != t.columns.size()) {
      throw std::logic_error("table row of " + std::to_string(row.size()) + " cells for " +
                             std::to_string(t.columns.size()) + " columns");
    }
  }
}

void typed_print_csv(const TypedTable& t, std::ostream& out) {
  std::string line;
  for (const auto& c : t.columns) {
    for (const auto& p : c.parts) {
      // Appended apart: `"," + std::string` makes GCC 12 warn falsely (-Wrestrict, PR105329).
      if (!line.empty()) line += ",";
      line += typed_csv_cell(p);
    }
  }
  out << line << "\n";
  for (const auto& row : t.rows) {
    line.clear();
    bool first = true;
    for (std::size_t i = 0; i < t.columns.size(); ++i) {
      for (std::size_t k = 0; k < t.columns[i].parts.size(); ++k) {
        const TypedPart v = typed_part(t.columns[i], row[i], k);
        if (!first) line += ",";
        first = false;
        if (!v) continue;  // missing: an empty field
        line += std::holds_alternative<double>(*v) ? shortest_double(std::get<double>(*v))
                                                   : typed_csv_cell(std::get<std::string>(*v));
      }
    }
    out << line << "\n";
  }
}

void typed_print_json(const TypedTable& t, std::ostream& out) {
  using Json = nlohmann::ordered_json;
  Json columns = Json::array();
  for (const auto& c : t.columns) {
    for (const auto& p : c.parts) {
      columns.push_back({{"name", p}, {"header", c.header}, {"label", c.label}});
    }
  }
  Json rows = Json::array();
  for (const auto& row : t.rows) {
    Json r = Json::object();
    for (std::size_t i = 0; i < t.columns.size(); ++i) {
      for (std::size_t k = 0; k < t.columns[i].parts.size(); ++k) {
        const TypedPart v = typed_part(t.columns[i], row[i], k);
        Json value = nullptr;
        if (v && std::holds_alternative<double>(*v)) value = std::get<double>(*v);
        if (v && std::holds_alternative<std::string>(*v)) value = std::get<std::string>(*v);
        r[t.columns[i].parts[k]] = value;
      }
    }
    rows.push_back(std::move(r));
  }
  out << Json{{"table", {{"columns", columns}, {"rows", rows}}}}.dump() << "\n";
}

}  // namespace

TableColumn label_column(std::string header, std::string name) {
  return {std::move(header), {std::move(name)}, true};
}

TableColumn number_column(std::string header, const std::string& name, const std::string& unit) {
  return {std::move(header), {typed_with_unit(name, unit)}, false};
}

TableColumn mean_std_column(std::string header, const std::string& name, const std::string& unit) {
  return {std::move(header),
          {typed_with_unit(name + "_mean", unit), typed_with_unit(name + "_std", unit)},
          false};
}

TableColumn pair_column(std::string header, std::string first, std::string second) {
  return {std::move(header), {std::move(first), std::move(second)}, false};
}

std::string machine_name(const std::string& text) {
  std::string s;
  bool gap = false;
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (std::isalnum(u) || c == '.') {
      if (gap && !s.empty()) s += '_';
      gap = false;
      s += static_cast<char>(std::tolower(u));
    } else {
      gap = true;
    }
  }
  return s;
}

TableCell number_cell(double value, std::string text) {
  TableCell c(std::move(text));
  c.numbers = {value};
  c.typed = true;
  return c;
}

TableCell mean_std_cell(double mean, double std, std::string text) {
  TableCell c(std::move(text));
  c.numbers = {mean, std};
  c.typed = true;
  return c;
}

TableCell pair_cell(double first, double second, std::string text) {
  TableCell c(std::move(text));
  c.numbers = {first, second};
  c.typed = true;
  return c;
}

TableCell missing_cell(std::string text) {
  TableCell c(std::move(text));
  c.typed = true;
  return c;
}

TableCell label_cell(std::string text, std::string key) {
  TableCell c(std::move(text));
  c.key = std::move(key);
  c.typed = true;
  return c;
}

TextTable TypedTable::text_table() const {
  TextTable t;
  for (const auto& c : columns) t.header.push_back(c.header);
  for (const auto& row : rows) {
    std::vector<std::string> cells;
    for (const auto& cell : row) cells.push_back(cell.text);
    t.rows.push_back(std::move(cells));
  }
  return t;
}

void TypedTable::print(std::ostream& out, TableFormat format) const {
  typed_check(*this);
  switch (format) {
    case TableFormat::csv:
      return typed_print_csv(*this, out);
    case TableFormat::json:
      return typed_print_json(*this, out);
    default:
      return text_table().print(out, format);
  }
}

}  // namespace cnclab
