#include "cnclab/core/progress.hpp"

#include <gtest/gtest.h>

#include <sstream>

namespace cnclab {
namespace {

TEST(Progress, QuietPrintsNothing) {
  std::ostringstream out;
  {
    Progress p("train", 10, out, {ProgressMode::quiet, 0.0, 0.0});
    for (std::size_t i = 0; i <= 10; ++i) p.update(i);
  }
  EXPECT_EQ(out.str(), "");
}

TEST(Progress, PlainModePrintsWholeLinesWithoutCarriageReturns) {
  std::ostringstream out;
  {
    Progress p("train", 4, out, {ProgressMode::plain, 0.0, 0.0});
    for (std::size_t i = 1; i <= 4; ++i) p.update(i, "loss 1");
  }
  const std::string s = out.str();
  EXPECT_EQ(s.find('\r'), std::string::npos);
  EXPECT_NE(s.find("train 4/4 (100%)"), std::string::npos) << s;
  EXPECT_NE(s.find("loss 1"), std::string::npos);
}

TEST(Progress, TerminalModeRedrawsInPlaceWithEta) {
  std::ostringstream out;
  {
    Progress p("train", 2, out, {ProgressMode::terminal, 0.0, 0.0});
    p.update(1);
  }
  const std::string s = out.str();
  EXPECT_EQ(s.front(), '\r');
  EXPECT_NE(s.find("ETA"), std::string::npos);
  EXPECT_EQ(s.back(), '\n');
}

TEST(Progress, StagedProgressGivesEachStageItsLineInOrder) {
  std::ostringstream out;
  {
    StagedProgress staged("dataset", out, {ProgressMode::plain, 0.0, 0.0});
    const ProgressCallback report = staged.callback();
    for (std::size_t i = 1; i <= 3; ++i) report("plan", i, 3);
    for (std::size_t i = 1; i <= 2; ++i) report("simulate", i, 2);
  }
  const std::string s = out.str();
  const auto plan = s.find("dataset: plan 3/3 (100%)"), sim = s.find("dataset: simulate 2/2");
  ASSERT_NE(plan, std::string::npos) << s;
  ASSERT_NE(sim, std::string::npos) << s;
  EXPECT_LT(plan, sim);
  EXPECT_EQ(s.find("dataset: plan", sim), std::string::npos) << "a finished stage reappeared";
}

TEST(Progress, DurationFormat) {
  EXPECT_EQ(Progress::format_duration(12.34), "12.3s");
  EXPECT_EQ(Progress::format_duration(185), "3m05s");
  EXPECT_EQ(Progress::format_duration(3720), "1h02m");
}

}  // namespace
}  // namespace cnclab
