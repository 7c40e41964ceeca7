// Near-constant targets (data/constant_targets.hpp): the rule on hand-made
// targets, and on real step-error datasets: an inclined plane, whose step
// errors are exactly 0 in theory (what the program computes is rounding
// noise), is flagged through the generator's declared resolution; the
// seed-000 surface 1 is not.
#include "cnclab/data/constant_targets.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cnclab/core/config.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/data/generator.hpp"

namespace cnclab {
namespace {

Dataset with_targets(const Eigen::MatrixXd& y) {
  Dataset d;
  d.inputs = Eigen::MatrixXd::Zero(1, y.cols());
  d.targets = y;
  for (Eigen::Index r = 0; r < y.rows(); ++r) {
    std::string name = "y";  // appended: GCC 12 warns falsely on "y" + (-Wrestrict, PR105329)
    name += std::to_string(r);
    d.target_names.push_back(name);
    d.target_units.push_back("µm");
  }
  return d;
}

Eigen::MatrixXd noise(Eigen::Index n, double mean, double std, std::uint64_t seed) {
  Rng rng(seed);
  Eigen::MatrixXd y(1, n);
  for (Eigen::Index j = 0; j < n; ++j) y(0, j) = rng.normal(mean, std);
  return y;
}

TEST(ConstantTargets, RuleOnHandMadeTargets) {
  // A constant plus noise at 1e-9 of it: relative clause.
  auto c = constant_targets(with_targets(noise(50, 5.0, 5e-9, 1)), {});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].name, "y0");
  EXPECT_NEAR(c[0].magnitude, 5.0, 1e-6);
  // Noise around zero has no magnitude to be relative to: only a declared
  // resolution catches it.
  const Dataset zero = with_targets(noise(50, 0.0, 1e-11, 2));
  EXPECT_TRUE(constant_targets(zero, {}).empty());
  EXPECT_EQ(constant_targets(zero, {1e-6}).size(), 1u);
  // Real spread: none.
  EXPECT_TRUE(constant_targets(with_targets(noise(50, 5.0, 0.5, 3)), {1e-6}).empty());
  // One sample has no spread to judge; NaN makes no clause true.
  EXPECT_TRUE(constant_targets(with_targets(Eigen::MatrixXd::Constant(1, 1, 2.0)), {}).empty());
  Eigen::MatrixXd with_nan = noise(50, 0.0, 1e-11, 4);
  with_nan(0, 7) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(constant_targets(with_targets(with_nan), {1e-6}).empty());
  // Exactly constant (zero spread) is caught at any magnitude, zero included.
  EXPECT_EQ(constant_targets(with_targets(Eigen::MatrixXd::Zero(1, 9)), {}).size(), 1u);
  // Per row: only the flat one of two, named in the warning.
  Eigen::MatrixXd two(2, 50);
  two.row(0) = noise(50, 1.0, 0.3, 5);
  two.row(1) = noise(50, 0.0, 1e-12, 6);
  const auto rows = constant_targets(with_targets(two), {1e-6, 1e-6});
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(constant_targets_warning(rows), "constant targets (y1)");
  EXPECT_NE(constant_target_text(rows[0]).find("below the generator's resolution 1e-06 µm"),
            std::string::npos)
      << constant_target_text(rows[0]);
}

// A step-error dataset on `surface` (inline YAML map), 6 lines x 8 points.
Dataset step_error_dataset(const std::string& surface,
                           std::shared_ptr<const DatasetGenerator>& generator) {
  const ConfigDocument doc = ConfigDocument::parse(
      "dataset:\n  generator: step_error\n  options:\n    surface: " + surface +
          "\n    lines: 6\n    points_per_line: 8\n    tool_radius: 5\n    curve_points: 3\n",
      "test");
  generator = read_generator(doc.root().section("dataset"));
  Rng rng(1);
  return generator->generate(rng);
}

TEST(ConstantTargets, AnInclinedPlaneIsFlaggedAFreeFormSurfaceIsNot) {
  std::shared_ptr<const DatasetGenerator> g;
  // z = 10 + 0.18 (x - 260), like the plane face of the CAD example.
  const Dataset plane = step_error_dataset(
      "{degree_u: 1, degree_v: 1, knots_u: [0, 0, 1, 1], knots_v: [0, 0, 1, 1], "
      "control_points: [[[260, 0, 10], [260, 50, 10]], [[298, 0, 16.84], [298, 50, 16.84]]]}",
      g);
  ASSERT_EQ(plane.targets.rows(), 1);
  EXPECT_LT(plane.targets.cwiseAbs().maxCoeff(), 1e-9);  // µm: numerical zero
  const auto flat = constant_targets(plane, g->target_resolution());
  ASSERT_EQ(flat.size(), 1u);
  EXPECT_EQ(flat[0].name, "step_error");
  const Dataset free_form = step_error_dataset(
      std::string("\"") + CNCLAB_SOURCE_DIR "/configs/surfaces/surface1.yaml\"", g);
  EXPECT_TRUE(constant_targets(free_form, g->target_resolution()).empty());
}

}  // namespace
}  // namespace cnclab
