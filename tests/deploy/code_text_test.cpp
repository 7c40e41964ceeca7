// Exact number literals (read back by the C library's own strtod/strtof, an
// independent parser), identifiers and precision names of the exports.
#include "cnclab/deploy/code_text.hpp"

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"

namespace cnclab {
namespace {

std::uint64_t bits(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

TEST(CodeText, HexDoublesReadBackBitForBit) {
  std::vector<double> values = {0.0,      -0.0,    1.0,
                                -2.5,     0.1,     1e-300,
                                DBL_MIN,  DBL_MAX, std::numeric_limits<double>::denorm_min(),
                                -3.0e-320};
  Rng rng(7);
  for (int i = 0; i < 2000; ++i) {
    values.push_back((rng.uniform() - 0.5) * std::pow(10.0, 40.0 * (rng.uniform() - 0.5)));
  }
  for (const double x : values) {
    const std::string text = hex_double(x);
    char* end = nullptr;
    const double back = std::strtod(text.c_str(), &end);
    EXPECT_EQ(*end, '\0') << text;
    EXPECT_EQ(bits(back), bits(x)) << text;
  }
}

TEST(CodeText, FloatLiteralsAreTheRoundedFloatExactly) {
  Rng rng(8);
  for (int i = 0; i < 2000; ++i) {
    const double x = (rng.uniform() - 0.5) * std::pow(10.0, 20.0 * (rng.uniform() - 0.5));
    const float f = static_cast<float>(x);
    const std::string text = hex_float(f);
    ASSERT_EQ(text.back(), 'f') << text;
    EXPECT_EQ(std::strtof(text.substr(0, text.size() - 1).c_str(), nullptr), f) << text;
    const CCodeContext c{"m", CPrecision::float32};
    EXPECT_EQ(std::strtof(c.literal(x).c_str(), nullptr), f) << c.literal(x);
  }
  const CCodeContext d{"m", CPrecision::float64};
  EXPECT_EQ(d.literal(2.0), "2.0");
  EXPECT_EQ(CCodeContext({"m", CPrecision::float32}).literal(-1.0), "-1.0f");
  EXPECT_EQ(d.literal(0.5), "0.5");
  EXPECT_EQ(d.literal(0.1), "0.1");
  EXPECT_EQ(d.literal(1.0 / 3.0), hex_double(1.0 / 3.0));
  EXPECT_EQ(CCodeContext({"m", CPrecision::float32}).literal(0.1), hex_float(0.1f));
  EXPECT_EQ(d.math("tanh"), "tanh");
  EXPECT_EQ(CCodeContext({"m", CPrecision::float32}).math("tanh"), "tanhf");
  EXPECT_EQ(d.real(), "m_real");
}

TEST(CodeText, IdentifiersFromExperimentNames) {
  EXPECT_EQ(export_identifier("step_error_surface1"), "step_error_surface1");
  EXPECT_EQ(export_identifier("IK-x.v2"), "ik_x_v2");
  EXPECT_EQ(export_identifier("2nd"), "n_2nd");
  EXPECT_NO_THROW(check_export_identifier("contour_error_narx"));
  for (const char* bad : {"", "1abc", "int", "a-b", "ab c", "a\xc3\xa4"}) {
    EXPECT_THROW(check_export_identifier(bad), ConfigError) << bad;
  }
  EXPECT_THROW(check_export_identifier(std::string(41, 'a')), ConfigError);
  EXPECT_EQ(parse_precision("float"), CPrecision::float32);
  EXPECT_EQ(parse_precision("double"), CPrecision::float64);
  EXPECT_THROW(parse_precision("half"), ConfigError);
}

}  // namespace
}  // namespace cnclab
