#include "cnclab/report/text_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

// Display width: UTF-8 continuation bytes take no column (±, Δ, —).
std::size_t width(const std::string& s) {
  return static_cast<std::size_t>(
      std::count_if(s.begin(), s.end(), [](char c) { return (c & 0xC0) != 0x80; }));
}

std::string csv_cell(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

void TextTable::print_aligned(std::ostream& out) const {
  std::vector<std::size_t> w(header.size(), 0);
  for (std::size_t c = 0; c < header.size(); ++c) w[c] = width(header[c]);
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size() && c < w.size(); ++c)
      w[c] = std::max(w[c], width(row[c]));
  }
  const auto line = [&](const std::vector<std::string>& cells) {
    std::string s;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      s += cells[c];
      if (c + 1 < cells.size()) s += std::string(w[c] - width(cells[c]) + 2, ' ');
    }
    out << s << "\n";
  };
  line(header);
  std::vector<std::string> rule;
  for (std::size_t c = 0; c < w.size(); ++c) rule.push_back(std::string(w[c], '-'));
  line(rule);
  for (const auto& row : rows) line(row);
}

void TextTable::print_markdown(std::ostream& out) const {
  const auto line = [&](const std::vector<std::string>& cells) {
    out << "|";
    for (const auto& cell : cells) {
      std::string escaped;
      for (char ch : cell) escaped += ch == '|' ? std::string("\\|") : std::string(1, ch);
      out << " " << escaped << " |";
    }
    out << "\n";
  };
  line(header);
  out << "|";
  for (std::size_t c = 0; c < header.size(); ++c) out << "---|";
  out << "\n";
  for (const auto& row : rows) line(row);
}

void TextTable::print_csv(std::ostream& out) const {
  const auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) out << (c ? "," : "") << csv_cell(cells[c]);
    out << "\n";
  };
  line(header);
  for (const auto& row : rows) line(row);
}

void TextTable::print_latex(std::ostream& out) const {
  out << "\\begin{tabular}{" << std::string(header.size(), 'l') << "}\n\\hline\n";
  const auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c)
      out << (c ? " & " : "") << latex_escape(cells[c]);
    out << " \\\\\n";
  };
  line(header);
  out << "\\hline\n";
  for (const auto& row : rows) line(row);
  out << "\\hline\n\\end{tabular}\n";
}

void TextTable::print_json(std::ostream& out) const {
  using Json = nlohmann::ordered_json;
  Json columns = Json::array();
  for (const auto& h : header) columns.push_back({{"name", h}, {"header", h}, {"label", true}});
  Json records = Json::array();
  for (const auto& row : rows) {
    Json r = Json::object();
    for (std::size_t c = 0; c < row.size() && c < header.size(); ++c) r[header[c]] = row[c];
    records.push_back(std::move(r));
  }
  out << Json{{"table", {{"columns", columns}, {"rows", records}}}}.dump() << "\n";
}

void TextTable::print(std::ostream& out, TableFormat format) const {
  switch (format) {
    case TableFormat::text:
      return print_aligned(out);
    case TableFormat::markdown:
      return print_markdown(out);
    case TableFormat::csv:
      return print_csv(out);
    case TableFormat::latex:
      return print_latex(out);
    case TableFormat::json:
      return print_json(out);
  }
}

TableFormat parse_table_format(const std::string& name) {
  if (name == "text") return TableFormat::text;
  if (name == "md") return TableFormat::markdown;
  if (name == "csv") return TableFormat::csv;
  if (name == "latex") return TableFormat::latex;
  if (name == "json") return TableFormat::json;
  throw ConfigError("--format: unknown format '" + name +
                    "'; choose one of: text, md, csv, latex, json");
}

void print_table_title(std::ostream& out, TableFormat format, const std::string& title) {
  switch (format) {
    case TableFormat::text:
      out << "\n" << title << "\n\n";
      return;
    case TableFormat::markdown:
      out << "\n### " << title << "\n\n";
      return;
    case TableFormat::csv:
      out << "\n# " << title << "\n";
      return;
    case TableFormat::latex:
      out << "\n% " << title << "\n";
      return;
    case TableFormat::json:
      out << nlohmann::json{{"title", title}}.dump() << "\n";
      return;
  }
}

void print_table_notes(std::ostream& out, TableFormat format,
                       const std::vector<std::string>& notes) {
  if (notes.empty()) return;
  switch (format) {
    case TableFormat::text:
      out << "\nNotes\n";
      for (const auto& n : notes) out << "- " << n << "\n";
      return;
    case TableFormat::markdown:
      out << "\n";
      for (const auto& n : notes) out << "- " << n << "\n";
      return;
    case TableFormat::csv:
      for (const auto& n : notes) out << "# " << n << "\n";
      return;
    case TableFormat::latex:
      for (const auto& n : notes) out << "% " << n << "\n";
      return;
    case TableFormat::json:
      out << nlohmann::json{{"notes", notes}}.dump() << "\n";
      return;
  }
}

std::string latex_escape(const std::string& text) {
  std::string s;
  for (char c : text) {
    switch (c) {
      case '\\':
        s += "\\textbackslash{}";
        break;
      case '~':
        s += "\\textasciitilde{}";
        break;
      case '^':
        s += "\\textasciicircum{}";
        break;
      case '&':
      case '%':
      case '$':
      case '#':
      case '_':
      case '{':
      case '}':
        s += '\\';
        s += c;
        break;
      default:
        s += c;
    }
  }
  return s;
}

std::string table_number(double value, int digits) {
  if (std::isnan(value)) return "-";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

}  // namespace cnclab
