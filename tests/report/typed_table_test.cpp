// TypedTable (typed_table.hpp): text, md and latex show the builder's texts
// exactly as a TextTable of the same strings; csv and json carry the numbers
// (read back by nlohmann::json and std::stod, a second path), split into the
// column's parts, missing as empty / null; a text cell in a number column is a
// builder's bug, not a silent string.
#include "cnclab/report/typed_table.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

namespace cnclab {
namespace {

TypedTable methods() {
  TypedTable t;
  t.columns = {label_column("method", "method"), pair_column("stable", "stable", "runs"),
               mean_std_column("contour RMS", "contour_rms", "um"),
               number_column("max |e| (µm)", "max_abs", "um")};
  t.rows.push_back({"two_stage", pair_cell(4, 5, "4/5"), mean_std_cell(5.0123, 0.83, "5.01 ± 0.83"),
                    number_cell(0.1, "0.1")});
  t.rows.push_back({label_cell("zero predictor, e = 0", "zero"), missing_cell("-"),
                    number_cell(7.5, "7.5"), missing_cell("n/a")});
  return t;
}

std::string typed_render(const TypedTable& t, TableFormat f) {
  std::ostringstream out;
  t.print(out, f);
  return out.str();
}

TEST(TypedTable, PeoplesFormatsAreTheTextTableOfTheTexts) {
  TextTable same;
  same.header = {"method", "stable", "contour RMS", "max |e| (µm)"};
  same.rows = {{"two_stage", "4/5", "5.01 ± 0.83", "0.1"},
               {"zero predictor, e = 0", "-", "7.5", "n/a"}};
  for (const TableFormat f : {TableFormat::text, TableFormat::markdown, TableFormat::latex}) {
    std::ostringstream expected;
    same.print(expected, f);
    EXPECT_EQ(typed_render(methods(), f), expected.str());
  }
}

TEST(TypedTable, CsvCarriesThePartsAsNumbers) {
  // A label_cell's key, not its text, is what programs match on.
  EXPECT_EQ(typed_render(methods(), TableFormat::csv),
            "method,stable,runs,contour_rms_mean_um,contour_rms_std_um,max_abs_um\n"
            "two_stage,4,5,5.0123,0.83,0.1\n"
            "zero,,,7.5,,\n");
  TypedTable t = methods();
  t.rows[1][0] = "zero predictor, e = 0";  // a text label: quoted (RFC 4180)
  EXPECT_NE(typed_render(t, TableFormat::csv).find("\n\"zero predictor, e = 0\",,,7.5,,\n"),
            std::string::npos);
}

TEST(TypedTable, JsonRowsByColumnNameWithNulls) {
  const auto j = nlohmann::json::parse(typed_render(methods(), TableFormat::json));
  const auto& table = j.at("table");
  ASSERT_EQ(table.at("columns").size(), 6u);
  EXPECT_EQ(table.at("columns")[0].at("label"), true);
  EXPECT_EQ(table.at("columns")[3].at("name"), "contour_rms_mean_um");
  EXPECT_EQ(table.at("columns")[3].at("header"), "contour RMS");
  const auto& rows = table.at("rows");
  EXPECT_EQ(rows[0].at("stable"), 4);
  EXPECT_DOUBLE_EQ(rows[0].at("contour_rms_mean_um").get<double>(), 5.0123);
  EXPECT_EQ(rows[1].at("method"), "zero");
  EXPECT_TRUE(rows[1].at("runs").is_null());
  EXPECT_TRUE(rows[1].at("contour_rms_std_um").is_null());
  EXPECT_TRUE(rows[1].at("max_abs_um").is_null());
}

TEST(TypedTable, TextInANumberColumnOrTwiceNamedColumnIsABug) {
  TypedTable t = methods();
  t.rows[0][3] = "0.1";  // text only: the number would be lost in csv
  EXPECT_THROW(typed_render(t, TableFormat::csv), std::logic_error);
  EXPECT_NO_THROW(typed_render(t, TableFormat::text));
  TypedTable twice = methods();
  twice.columns[3] = number_column("again", "contour_rms_mean", "um");
  EXPECT_THROW(typed_render(twice, TableFormat::json), std::logic_error);
}

TEST(TypedTable, MachineNames) {
  EXPECT_EQ(machine_name("ours, tuned"), "ours_tuned");
  EXPECT_EQ(machine_name("X ours"), "x_ours");
  EXPECT_EQ(machine_name("ours, tuned, no dropout"), "ours_tuned_no_dropout");
  EXPECT_EQ(machine_name("(a) 0.5 µm"), "a_0.5_m");
}

}  // namespace
}  // namespace cnclab
