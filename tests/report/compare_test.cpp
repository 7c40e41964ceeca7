// `cnclab compare` (report/compare.hpp) on in-memory runs: an array of more
// than kAbbreviateScalars numbers (an inlined surface's control points)
// prints as its shape and hash, as `show` prints it, in every format; --full
// prints it whole.
#include "cnclab/report/compare.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "cnclab/core/config_abbreviate.hpp"

namespace cnclab {
namespace {

// A run whose surface has a 10 x 10 x 3 control net, shifted by `z`.
ComparedRun surface_run(const std::string& file, double z) {
  std::string net = "[";
  for (int i = 0; i < 10; ++i) {
    net += i ? ", [" : "[";
    for (int j = 0; j < 10; ++j) {
      net += (j ? ", [" : "[") + std::to_string(i) + ", " + std::to_string(j) + ", " +
             std::to_string(z + 0.01 * i * j) + "]";
    }
    net += "]";
  }
  net += "]";
  ComparedRun r;
  r.file = file;
  r.record.experiment = "e";
  r.record.resolved_yaml =
      "name: e\ndataset:\n  options:\n    surface:\n      control_points: " + net +
      "\n      degree_u: 3\n";
  r.record.metrics = {{"rmse", 1.0 + z}};
  return r;
}

std::size_t longest_line(const std::string& text) {
  std::size_t longest = 0;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) longest = std::max(longest, line.size());
  return longest;
}

TEST(Compare, LargeArraysPrintAsShapeAndHashUnlessFull) {
  const std::vector<ComparedRun> runs = {surface_run("a.h5", 0.0), surface_run("b.h5", 0.5)};
  for (const auto format :
       {CompareFormat::table, CompareFormat::markdown, CompareFormat::csv, CompareFormat::json}) {
    std::ostringstream out;
    print_comparison(runs, format, out);
    // The differing key is there, its values as "10 × 10 × 3, hash ...".
    EXPECT_NE(out.str().find("dataset.options.surface.control_points"), std::string::npos);
    EXPECT_NE(out.str().find("10 × 10 × 3, hash "), std::string::npos) << out.str();
    EXPECT_LT(longest_line(out.str()), 200u) << out.str();
  }
  std::ostringstream full;
  print_comparison(runs, CompareFormat::table, full, true);
  EXPECT_EQ(full.str().find("hash "), std::string::npos);
  EXPECT_NE(full.str().find("[9, 9, 1.31"), std::string::npos) << full.str();  // 0.5 + 0.81
  EXPECT_GT(longest_line(full.str()), 1000u);
}

}  // namespace
}  // namespace cnclab
