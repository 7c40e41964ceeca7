// TextTable renderers: CSV read back by an independent RFC 4180 parser,
// Markdown cell escaping, LaTeX escaping and tabular structure.
#include "cnclab/report/text_table.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "cnclab/core/error.hpp"

namespace cnclab {
namespace {

// RFC 4180 reader: fields separated by ',', quoted fields may hold ',', '\n'
// and doubled quotes; records end at an unquoted '\n'.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> record;
  std::string field;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
        field += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        field += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      record.push_back(field);
      field.clear();
    } else if (c == '\n') {
      record.push_back(field);
      field.clear();
      records.push_back(record);
      record.clear();
    } else {
      field += c;
    }
  }
  EXPECT_FALSE(quoted) << "unterminated quote";
  EXPECT_TRUE(field.empty() && record.empty()) << "missing final newline";
  return records;
}

TextTable awkward() {
  TextTable t;
  t.header = {"Absolute error (µm)", "a, b", "say \"hi\""};
  t.rows = {{"< 0.1", "60.88", "multi\nline"}, {"", "x|y", "50 % & $5_#{~^}\\"}};
  return t;
}

std::string render(const TextTable& t, TableFormat f) {
  std::ostringstream out;
  t.print(out, f);
  return out.str();
}

TEST(TextTable, CsvRoundTrip) {
  const TextTable t = awkward();
  const auto records = parse_csv(render(t, TableFormat::csv));
  ASSERT_EQ(records.size(), 1 + t.rows.size());
  EXPECT_EQ(records[0], t.header);
  for (std::size_t r = 0; r < t.rows.size(); ++r) EXPECT_EQ(records[r + 1], t.rows[r]);
}

TEST(TextTable, MarkdownEscapesPipes) {
  TextTable t;
  t.header = {"a", "b"};
  t.rows = {{"x|y", "1"}};
  EXPECT_EQ(render(t, TableFormat::markdown), "| a | b |\n|---|---|\n| x\\|y | 1 |\n");
}

TEST(TextTable, LatexEscaping) {
  EXPECT_EQ(latex_escape("50 % & $5_#{~^}\\"),
            "50 \\% \\& \\$5\\_\\#\\{\\textasciitilde{}\\textasciicircum{}\\}"
            "\\textbackslash{}");
  EXPECT_EQ(latex_escape("0.1–0.2 µm"), "0.1–0.2 µm");  // UTF-8 untouched
}

TEST(TextTable, LatexTabular) {
  TextTable t;
  t.header = {"p", "MSE"};
  t.rows = {{"0.5", "0.004"}, {"a_b", "1"}};
  EXPECT_EQ(render(t, TableFormat::latex),
            "\\begin{tabular}{ll}\n\\hline\np & MSE \\\\\n\\hline\n0.5 & 0.004 \\\\\n"
            "a\\_b & 1 \\\\\n\\hline\n\\end{tabular}\n");
}

TEST(TextTable, FormatNames) {
  EXPECT_EQ(parse_table_format("text"), TableFormat::text);
  EXPECT_EQ(parse_table_format("md"), TableFormat::markdown);
  EXPECT_EQ(parse_table_format("csv"), TableFormat::csv);
  EXPECT_EQ(parse_table_format("latex"), TableFormat::latex);
  try {
    parse_table_format("html");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("'html'"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("md, csv, latex"), std::string::npos);
  }
}

TEST(TextTable, NotesAreCommentsInCsvAndLatex) {
  const auto notes = [](TableFormat f) {
    std::ostringstream out;
    print_table_title(out, f, "Table 2");
    print_table_notes(out, f, {"one", "two"});
    return out.str();
  };
  EXPECT_EQ(notes(TableFormat::csv), "\n# Table 2\n# one\n# two\n");
  EXPECT_EQ(notes(TableFormat::latex), "\n% Table 2\n% one\n% two\n");
  EXPECT_EQ(notes(TableFormat::markdown), "\n### Table 2\n\n\n- one\n- two\n");
}

}  // namespace
}  // namespace cnclab
