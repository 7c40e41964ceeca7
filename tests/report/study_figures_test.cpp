// The pieces of `cnclab report` that read files: base64 (RFC 4648 section
// 10's test vectors), a PNG's size and resolution (a PNG assembled here by
// the PNG specification's chunk layout), the figures section, and a sweep's
// parameter importance (summary.h5 /importance, malformed ones refused).
// The page in a real browser: tests/cli/report_browser_test.py.
#include "cnclab/report/study_figures.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "cnclab/core/error.hpp"
#include "cnclab/io/h5.hpp"
#include "cnclab/report/parameter_importance.hpp"
#include "common/temp_dir.hpp"

namespace cnclab {
namespace {

using testing::TempDir;

TEST(Base64, Rfc4648TestVectors) {
  EXPECT_EQ(base64_encode(""), "");
  EXPECT_EQ(base64_encode("f"), "Zg==");
  EXPECT_EQ(base64_encode("fo"), "Zm8=");
  EXPECT_EQ(base64_encode("foo"), "Zm9v");
  EXPECT_EQ(base64_encode("foob"), "Zm9vYg==");
  EXPECT_EQ(base64_encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(base64_encode("foobar"), "Zm9vYmFy");
  EXPECT_EQ(base64_encode(std::string("\xff\xfe\x00", 3)), "//4A");
}

std::string be32(std::uint32_t v) {
  return {static_cast<char>(v >> 24), static_cast<char>(v >> 16), static_cast<char>(v >> 8),
          static_cast<char>(v)};
}
// A chunk: length, type, data, CRC (not checked by png_info: zeros).
std::string chunk(const std::string& type, const std::string& data) {
  return be32(static_cast<std::uint32_t>(data.size())) + type + data + be32(0);
}

TEST(PngInfo, SizeAndResolutionFromIhdrAndPhys) {
  const std::string signature = "\x89PNG\r\n\x1a\n";
  const std::string ihdr = chunk("IHDR", be32(2100) + be32(900) + std::string("\x08\x06\0\0\0", 5));
  // 300 dpi = 11811 pixels per metre (unit 1).
  const std::string phys = chunk("pHYs", be32(11811) + be32(11811) + std::string(1, '\x01'));
  const auto info = png_info(signature + ihdr + phys + chunk("IDAT", "x") + chunk("IEND", ""));
  ASSERT_TRUE(info);
  EXPECT_EQ(info->width, 2100u);
  EXPECT_EQ(info->height, 900u);
  EXPECT_NEAR(info->dpi, 300.0, 0.01);
  const auto no_phys = png_info(signature + ihdr + chunk("IEND", ""));
  ASSERT_TRUE(no_phys);
  EXPECT_EQ(no_phys->dpi, 0.0);
  EXPECT_FALSE(png_info("GIF89a not a png at all, long enough to have a header"));
}

TEST(StudyFigures, EmbedsEachPngAndSaysWhatIsMissing) {
  TempDir dir;
  const std::string png = "\x89PNG\r\n\x1a\n" +
                          chunk("IHDR", be32(4) + be32(2) + std::string("\x08\x06\0\0\0", 5)) +
                          chunk("IEND", "");
  std::filesystem::create_directories(dir / "figures/step_error");
  std::ofstream(dir / "figures/step_error/fig5_loss.png", std::ios::binary) << png;
  std::ofstream(dir / "figures/step_error/.fig6.png.partial.png", std::ios::binary) << png;
  std::ofstream(dir / "figures/step_error/notes.txt") << "not a figure";
  HtmlPage page("t");
  StudyFigureOptions o;
  o.figures_dir = dir / "figures";
  o.topics = {"step_error", "feedrate"};
  EXPECT_EQ(add_study_figures(page, o), 1u);
  const std::string html = page.html();
  EXPECT_NE(html.find("src=\"data:image/png;base64," + base64_encode(png) + "\""),
            std::string::npos);
  EXPECT_EQ(html.find("partial"), std::string::npos);
  EXPECT_NE(html.find("No figures in " + (dir / "figures/feedrate").string()), std::string::npos);
  // Over the budget: named, not embedded.
  HtmlPage small("t");
  o.budget_bytes = 10;
  EXPECT_EQ(add_study_figures(small, o), 0u);
  EXPECT_NE(small.html().find("left out to keep the page small"), std::string::npos);
}

TEST(ParameterImportance, ReadsTheLayoutAndRefusesMalformedGroups) {
  TempDir dir;
  const auto write = [&](const std::string& name, const std::vector<std::string>& keys,
                         const std::vector<double>& values) {
    auto f = H5File::create(dir / name);
    f.create_group("/importance");
    f.set_attribute("/importance", "evaluator", "fanova");
    f.write_strings("/importance/parameter", keys);
    f.write_vector("/importance/value", values);
    f.close();
    return dir / name;
  };
  const auto ok = read_parameter_importance(write("ok.h5", {"a", "b", "c"}, {0.1, 0.6, 0.3}));
  ASSERT_TRUE(ok);
  EXPECT_EQ(ok->evaluator, "fanova");
  ASSERT_EQ(ok->values.size(), 3u);
  EXPECT_EQ(ok->values[0].first, "b");  // largest first
  EXPECT_EQ(ok->values[2].first, "a");
  EXPECT_THROW(read_parameter_importance(write("short.h5", {"a", "b"}, {0.5})), IoError);
  EXPECT_THROW(read_parameter_importance(write("nan.h5", {"a"}, {std::nan("")})), IoError);
  {
    auto f = H5File::create(dir / "none.h5");
    f.write_double("/x", 1);
    f.close();
  }
  EXPECT_FALSE(read_parameter_importance(dir / "none.h5"));
  // On the page: a malformed group is named, not drawn.
  HtmlPage page("t");
  add_parameter_importance(page, dir / "short.h5");
  EXPECT_NE(page.html().find("parameter importance not shown"), std::string::npos);
  EXPECT_EQ(page.html().find("<svg"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
