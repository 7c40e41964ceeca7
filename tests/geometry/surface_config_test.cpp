#include "cnclab/geometry/surface_config.hpp"

#include <gtest/gtest.h>

#include "cnclab/core/error.hpp"
#include "common/expect_error.hpp"
#include "geometry/shapes.hpp"

namespace cnclab {
namespace {

NurbsSurface parse(const std::string& text) {
  const ConfigDocument doc = ConfigDocument::parse(text, "surface.yaml");
  NurbsSurface s = read_nurbs_surface(doc.root());
  doc.check_all_consumed();
  return s;
}

std::string config_error(const std::string& text) {
  return testing::error_message<ConfigError>([&] { parse(text); });
}

TEST(SurfaceConfig, YamlRoundTripIsExact) {
  const NurbsSurface s = testing::sphere_patch(25.0, 0.7);
  const NurbsSurface back = parse(nurbs_surface_yaml(s, ""));
  EXPECT_EQ(back.degree_u, s.degree_u);
  EXPECT_EQ(back.knots_v, s.knots_v);
  ASSERT_EQ(back.points.size(), s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    EXPECT_EQ(back.points[i], s.points[i]);  // bit-exact: shortest round-trip text
    EXPECT_EQ(back.weights[i], s.weights[i]);
  }
}

const std::string kBilinear =
    "degree_u: 1\ndegree_v: 1\nknots_u: [0, 0, 1, 1]\nknots_v: [0, 0, 1, 1]\n"
    "control_points:\n  - [[0, 0, 0], [0, 1, 0]]\n  - [[1, 0, 0], [1, 1, 1]]\n";

TEST(SurfaceConfig, WeightsDefaultToOne) {
  const NurbsSurface s = parse(kBilinear);
  EXPECT_EQ(s.count_u, 2u);
  EXPECT_EQ(s.count_v, 2u);
  EXPECT_EQ(s.weights, std::vector<double>(4, 1.0));
  // Bilinear patch: S(0.5, 0.5) = mean of the corners.
  EXPECT_NEAR((surface_point(s, 0.5, 0.5) - Eigen::Vector3d(0.5, 0.5, 0.25)).norm(), 0, 1e-15);
}

TEST(SurfaceConfig, BadSurfacesGiveLocatedErrors) {
  EXPECT_NE(config_error(kBilinear + "weights: [[1, 1], [1, 0]]\n")
                .find("weights must be finite and > 0"),
            std::string::npos);
  EXPECT_NE(config_error(kBilinear + "weights: [[1, 1]]\n").find("one row per control-point row"),
            std::string::npos);
  std::string ragged = kBilinear;
  ragged.replace(ragged.find("[1, 1, 1]]"), 10, "[1, 1, 1], [2, 2, 2]]");
  EXPECT_NE(config_error(ragged).find("row 1 has 3 points, row 0 has 2"), std::string::npos);
  std::string two_d = kBilinear;
  two_d.replace(two_d.find("[1, 1, 1]"), 9, "[1, 1]");
  EXPECT_NE(config_error(two_d).find("point [1][1] must be [x, y, z]"), std::string::npos);
  std::string bad_knots = kBilinear;
  bad_knots.replace(bad_knots.find("knots_u: [0, 0, 1, 1]"), 21, "knots_u: [0, 1, 1]");
  const std::string knots_message = config_error(bad_knots);
  EXPECT_NE(knots_message.find("surface.yaml:"), std::string::npos) << knots_message;
  EXPECT_NE(knots_message.find("must have (control points + degree + 1) = 4"), std::string::npos)
      << knots_message;
  EXPECT_NE(config_error(kBilinear + "colour: red\n").find("colour"), std::string::npos);
  std::string degree = kBilinear;
  degree.replace(0, 11, "degree_u: 0");
  EXPECT_NE(config_error(degree).find("degree_u = 0: must be in [1, 15]"), std::string::npos);
}

}  // namespace
}  // namespace cnclab
