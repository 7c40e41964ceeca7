// CSV tables: an exact round trip, and every malformed input a ConfigError
// naming the file, the line and the column.
#include "cnclab/deploy/csv_table.hpp"

#include <gtest/gtest.h>

#include <fstream>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

std::filesystem::path write(const TempDir& dir, const std::string& text) {
  const auto p = dir / "t.csv";
  std::ofstream(p) << text;
  return p;
}

TEST(CsvTable, RoundTripIsExact) {
  TempDir dir;
  const std::vector<NamedColumn> columns = {
      {"a", "mm", (Eigen::VectorXd(3) << 0.1, -1e-300, 1.0 / 3.0).finished()},
      {"b", "", (Eigen::VectorXd(3) << 2.0, 1e20, -0.0).finished()}};
  const auto p = write(dir, csv_text({"made by a test", "key: value"}, columns));
  const auto back = read_csv_table(p);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].name, "a");
  EXPECT_EQ(back[0].unit, "mm");
  EXPECT_EQ(back[1].unit, "");
  for (std::size_t j = 0; j < 2; ++j) {
    for (Eigen::Index i = 0; i < 3; ++i) EXPECT_EQ(back[j].values[i], columns[j].values[i]);
  }
}

TEST(CsvTable, MalformedInputNamesFileLineAndColumn) {
  TempDir dir;
  const auto message = [&](const std::string& text) {
    return testing::error_message<ConfigError>([&] { read_csv_table(write(dir, text)); });
  };
  EXPECT_NE(message("").find("empty"), std::string::npos);
  EXPECT_NE(message("# only a comment\n").find("empty"), std::string::npos);
  EXPECT_NE(message("a,b\n").find("no rows"), std::string::npos);
  EXPECT_NE(message("a,b\n1,2\n3\n").find("t.csv:3: 1 values, the header names 2"),
            std::string::npos);
  EXPECT_NE(message("a,b\n1,x\n").find("t.csv:2 column 2 (b): 'x' is not a number"),
            std::string::npos);
  EXPECT_NE(message("a,b\n1,nan\n").find("NaN or infinity"), std::string::npos);
  EXPECT_NE(message("a,b\n1,-inf\n").find("NaN or infinity"), std::string::npos);
  EXPECT_NE(message("a,b\n1,1e999\n").find("NaN or infinity"), std::string::npos);
  EXPECT_NE(message("a,a\n1,2\n").find("appears twice"), std::string::npos);
  EXPECT_NE(message("a,\n1,2\n").find("without a name"), std::string::npos);
  EXPECT_NE(message("a [mm,b\n1,2\n").find("ends with ']'"), std::string::npos);
  EXPECT_NE(message("a [],b\n1,2\n").find("empty unit"), std::string::npos);
  EXPECT_NE(message("a,b\n1,\n").find("'' is not a number"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
