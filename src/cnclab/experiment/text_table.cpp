#include "cnclab/experiment/text_table.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

std::string table_number(double value, int digits) {
  if (std::isnan(value)) return "-";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, value);
  return buf;
}

}  // namespace cnclab
