// `cnclab dataset show`'s report (data/dataset_commands.hpp) of a dataset
// built by hand: its ranges, the histogram's bin counts and the
// convex/concave split, each worked out here from the values.
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "cnclab/data/dataset_commands.hpp"

namespace cnclab {
namespace {

// 20 samples, target y_j = j (0..19), one input x_j = 2 j; the first 5
// samples convex.
Dataset twenty_samples() {
  Dataset d;
  d.inputs.resize(1, 20);
  d.targets.resize(1, 20);
  d.metadata.resize(1, 20);
  for (int j = 0; j < 20; ++j) {
    d.inputs(0, j) = 2.0 * j;
    d.targets(0, j) = j;
    d.metadata(0, j) = j < 5 ? 1.0 : 0.0;
  }
  d.input_names = {"x"};
  d.input_units = {"mm"};
  d.target_names = {"y"};
  d.target_units = {"µm"};
  d.metadata_names = {"convex"};
  d.metadata_units = {"1"};
  d.generator = "by_hand";
  return d;
}

TEST(DatasetSummary, RangesHistogramAndConvexSplit) {
  std::ostringstream out;
  print_dataset_summary(twenty_samples(), "hand.h5", out);
  const std::string text = out.str();
  EXPECT_NE(text.find("dataset    hand.h5\ngenerator  by_hand\nsamples    20\n"), std::string::npos)
      << text;
  // min 0, max 38, mean 19 of x; min 0, max 19, mean 9.5 of y.
  EXPECT_NE(text.find("  x                           0             38             19  mm"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  y                           0             19            9.5  µm"),
            std::string::npos)
      << text;
  // 20 bins of width 19/20 over [0, 19]: one value in each, every bar full.
  EXPECT_NE(text.find("histogram of y [µm]\n"), std::string::npos);
  std::size_t full_bars = 0;
  for (std::size_t at = text.find("       1  " + std::string(40, '#') + "\n");
       at != std::string::npos;
       at = text.find("       1  " + std::string(40, '#') + "\n", at + 1)) {
    ++full_bars;
  }
  EXPECT_EQ(full_bars, 20u) << text;
  EXPECT_NE(text.find("[     18.05,         19]       1  "), std::string::npos) << text;  // closed
  EXPECT_NE(text.find("convex/concave split: convex 5 (25.0 %), concave 15 (75.0 %)"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("  convex   y in [0, 4] µm"), std::string::npos) << text;
  EXPECT_NE(text.find("  concave  y in [5, 19] µm"), std::string::npos) << text;
}

TEST(DatasetSummary, EmptyDatasetPrintsCountsOnly) {
  Dataset d;
  d.inputs.resize(1, 0);
  d.targets.resize(1, 0);
  d.generator = "by_hand";
  std::ostringstream out;
  print_dataset_summary(d, "empty.h5", out);
  EXPECT_NE(out.str().find("samples    0\n"), std::string::npos);
  EXPECT_EQ(out.str().find("histogram"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
