#include "cnclab/data/following_error.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "cnclab/core/config.hpp"
#include "cnclab/core/error.hpp"
#include "cnclab/data/generator.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

using testing::error_message;

// A short path (12 control points, 1.49 s), 3 runs, 1200 samples kept.
std::shared_ptr<const DatasetGenerator> small_generator(const std::string& extra = "",
                                                        const std::string& samples = "1200") {
  const std::string yaml =
      "dataset:\n  generator: following_error\n  options:\n"
      "    path: {control_points: 12}\n    runs: 3\n    samples: " +
      samples + "\n" + extra;
  const ConfigDocument doc = ConfigDocument::parse(yaml, "test.yaml");
  auto g = read_generator(doc.root().section("dataset"));
  doc.check_all_consumed();
  return g;
}

const Dataset& small_dataset() {
  static const Dataset d = [] {
    Rng rng(7);
    return small_generator()->generate(rng);
  }();
  return d;
}

double meta(const Dataset& d, const char* name, Eigen::Index k) {
  const Eigen::Index row = d.metadata_row(name);
  EXPECT_GE(row, 0) << name;
  return d.metadata(row, k);
}

TEST(FollowingErrorDataset, SampleCountsAndHalves) {
  const Dataset& d = small_dataset();
  ASSERT_EQ(d.num_samples(), 1200u);
  EXPECT_EQ(d.inputs.rows(), 2);
  EXPECT_EQ(d.targets.rows(), 2);
  EXPECT_EQ(first_validation_sample(d), 600u);
  for (Eigen::Index k = 0; k < 1200; ++k) {
    ASSERT_EQ(meta(d, "validation", k), k >= 600 ? 1.0 : 0.0) << k;
    // Time at the 1 ms controller period.
    ASSERT_NEAR(meta(d, "time", k), 1e-3 * static_cast<double>(k), 1e-12);
  }
}

TEST(FollowingErrorDataset, NormalisationIsExactlyMinusOneToOneAndInvertible) {
  const Dataset& d = small_dataset();
  const FollowingErrorRanges r = following_error_ranges(d);
  for (int a = 0; a < 2; ++a) {
    EXPECT_EQ(d.inputs.row(a).minCoeff(), -1.0);
    EXPECT_EQ(d.inputs.row(a).maxCoeff(), 1.0);
    EXPECT_EQ(d.targets.row(a).minCoeff(), -1.0);
    EXPECT_EQ(d.targets.row(a).maxCoeff(), 1.0);
    const char* v = a == 0 ? "v_ref_x" : "v_ref_y";
    const char* e = a == 0 ? "e_ref_x" : "e_ref_y";
    for (Eigen::Index k = 0; k < 1200; k += 7) {
      const double vp =
          r.velocity[a].min + (d.inputs(a, k) + 1) / 2 * (r.velocity[a].max - r.velocity[a].min);
      ASSERT_NEAR(vp, meta(d, v, k), 1e-9 * (r.velocity[a].max - r.velocity[a].min));
      const auto& er = r.following_error[a];
      ASSERT_NEAR(er.min + (d.targets(a, k) + 1) / 2 * (er.max - er.min), meta(d, e, k),
                  1e-9 * (er.max - er.min));
    }
  }
}

// The columns agree with each other: actual = ref - e, the contour columns
// are the motion module's estimates at those points, and the velocity is the
// derivative of the reference position.
TEST(FollowingErrorDataset, ColumnsAreConsistent) {
  const Dataset& d = small_dataset();
  for (Eigen::Index k = 1; k + 1 < 1200; k += 13) {
    for (const char* axis : {"x", "y"}) {
      const std::string s(axis);
      const double ref = meta(d, ("ref_" + s).c_str(), k);
      ASSERT_NEAR(meta(d, ("actual_" + s).c_str(), k),
                  ref - meta(d, ("e_ref_" + s).c_str(), k) / 1000, 1e-12);
      const double dv =
          (meta(d, ("ref_" + s).c_str(), k + 1) - meta(d, ("ref_" + s).c_str(), k - 1)) / 2e-3;
      ASSERT_NEAR(dv, meta(d, ("v_ref_" + s).c_str(), k), 0.05) << k;
    }
    PathPoint p;
    p.position = {meta(d, "ref_x", k), meta(d, "ref_y", k)};
    p.d1 = {meta(d, "d1_x", k), meta(d, "d1_y", k)};
    p.d2 = {meta(d, "d2_x", k), meta(d, "d2_y", k)};
    const Vec2 actual(meta(d, "actual_x", k), meta(d, "actual_y", k));
    ASSERT_NEAR(meta(d, "contour_tangent", k), tangent_line_contour_error(p, actual) * 1000, 1e-9);
    // Exact <= tangent-line distance is not guaranteed, but both are within
    // the following error's length.
    const double e = std::hypot(meta(d, "e_ref_x", k), meta(d, "e_ref_y", k));
    ASSERT_LE(meta(d, "contour_exact", k), e + 1e-9);
  }
  // The simulated machine lags: a following error of some µm, not zero.
  EXPECT_GT(d.metadata.row(d.metadata_row("e_ref_x")).cwiseAbs().maxCoeff(), 1.0);
}

TEST(FollowingErrorDataset, DeterministicWithTheSeed) {
  Rng a(7), b(8);
  const Dataset again = small_generator()->generate(a);
  EXPECT_EQ(again.content_hash(), small_dataset().content_hash());
  const Dataset other = small_generator()->generate(b);
  EXPECT_NE(other.content_hash(), small_dataset().content_hash());
}

TEST(FollowingErrorDataset, NormaliseRejectsNanAndConstantColumns) {
  Eigen::VectorXd x(4);
  x << 1, 2, std::numeric_limits<double>::quiet_NaN(), 4;
  const std::string m = error_message<Error>([&] { normalise_minmax(x, "v_ref_x"); });
  EXPECT_NE(m.find("v_ref_x: sample 2 is nan"), std::string::npos) << m;
  const std::string c =
      error_message<Error>([&] { normalise_minmax(Eigen::VectorXd::Constant(3, 2.0), "e"); });
  EXPECT_NE(c.find("constant column"), std::string::npos) << c;
  ColumnRange r;
  Eigen::VectorXd y(3);
  y << -3, 5, 1;
  const Eigen::VectorXd n = normalise_minmax(y, "y", &r);
  EXPECT_EQ(n[0], -1.0);
  EXPECT_EQ(n[1], 1.0);
  EXPECT_EQ(n[2], 0.0);
  EXPECT_EQ(r.min, -3.0);
  EXPECT_EQ(r.max, 5.0);
}

TEST(FollowingErrorDataset, BadOptionsAreConfigErrorsNamingTheKey) {
  auto message = [](const std::string& extra) {
    return error_message<ConfigError>([&] { small_generator(extra); });
  };
  EXPECT_NE(message("    limits: {velocity: 0}\n").find("limits.velocity"), std::string::npos);
  EXPECT_NE(message("    limits: {jerk: -5}\n").find("jerk"), std::string::npos);
  EXPECT_NE(message("    smoothing: 1.5\n").find("smoothing"), std::string::npos);
  EXPECT_NE(message("    runs: 0\n").find("runs"), std::string::npos);
  EXPECT_NE(message("    machine: {axes: {x: {position_gain: -1}}}\n").find("position_gain"),
            std::string::npos);
  EXPECT_NE(message("    smothing: 0.5\n").find("smothing"), std::string::npos);
}

TEST(FollowingErrorDataset, TooShortARunSaysWhatToChange) {
  Rng rng(7);
  const std::string m =
      error_message<Error>([&] { small_generator("", "100000000")->generate(rng); });
  EXPECT_NE(m.find("raise path.control_points"), std::string::npos) << m;
}

}  // namespace
}  // namespace cnclab
