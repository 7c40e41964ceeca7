// `cnclab surface show`'s report (report/cad_part_report.hpp) of a face
// summary made by hand: the header's unit note and probe path, and each
// cell's wording (a flat face's radius, a refusal, the clip share).
#include "cnclab/report/cad_part_report.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <sstream>

namespace cnclab {
namespace {

TEST(CadPartReport, HeaderAndCellsOfTwoFaces) {
  CadPartSummary part;
  part.unit = "inch";
  part.writer = "by hand";
  CadFaceSummary flat;
  flat.index = 1;
  flat.surface_type = "plane";
  flat.degree_u = flat.degree_v = 1;
  flat.axis_min = flat.axis_max = 1.0;
  flat.min_radius = std::numeric_limits<double>::infinity();
  flat.usable = "yes";
  flat.area = 100.0;
  CadFaceSummary refused = flat;
  refused.index = 2;
  refused.surface_type = "cone";
  refused.degree_u = 0;
  refused.min_radius = 2.5;
  refused.min_radius_concave = true;
  refused.usable = "undercut";
  refused.reason_text = "face 2: undercut at line 3";
  refused.clip_share = 0.25;
  part.faces = {flat, refused};
  ToolPathOptions path;
  path.lines = 10;
  path.points_per_line = 20;
  std::ostringstream out;
  print_cad_part("part.step", part, path, true, out);
  const std::string text = out.str();
  EXPECT_NE(text.find("part.step: 2 faces; unit inch (converted: lengths below are in mm); "
                      "written by by hand\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("use one as surface: {file: part.step, face: N}\n"), std::string::npos);
  EXPECT_NE(text.find("verdicts on a 10 x 20 probe path"), std::string::npos) << text;
  EXPECT_NE(text.find("∞ (flat)"), std::string::npos) << text;
  EXPECT_NE(text.find("2.5 concave"), std::string::npos) << text;
  EXPECT_NE(text.find("no: undercut"), std::string::npos) << text;
  EXPECT_NE(text.find("25 %"), std::string::npos) << text;                   // clip share
  EXPECT_NE(text.find("[1, 1]"), std::string::npos) << text;                 // n·axis range
  EXPECT_EQ(text.substr(text.size() - 27), "face 2: undercut at line 3\n");  // --why
  std::ostringstream quiet;
  print_cad_part("part.step", part, path, false, quiet);
  EXPECT_EQ(quiet.str().find("undercut at line"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
