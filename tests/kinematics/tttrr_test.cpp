// The TTTRR machine: forward kinematics against two independent
// formulations, inverse kinematics by round trip on random poses, the
// Jacobian by finite differences, the singularity, limits and bad input.
#include "cnclab/kinematics/tttrr.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <numbers>

#include "cnclab/core/config.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/kinematics/tttrr_config.hpp"
#include "common/expect_error.hpp"

namespace cnclab {
namespace {

constexpr double kPositionTol = 1e-9;      // mm
constexpr double kOrientationTol = 1e-12;  // rad (unit-vector components)

TttrrOptions test_machine() {
  TttrrOptions m;
  m.offset_d = 75.0;
  m.x = {-1000, 1000};
  m.y = {-1000, 1000};
  m.z = {-1000, 1000};
  m.a = {-std::numbers::pi / 2, std::numbers::pi / 2};
  m.c = {-std::numbers::pi, std::numbers::pi};
  return m;
}

Joints random_joints(Rng& rng) {
  return {rng.uniform(-200, 200), rng.uniform(-200, 200), rng.uniform(-200, 200),
          rng.uniform(-1.5, 1.5), rng.uniform(-3.1, 3.1)};
}

// An independent composition of elementary homogeneous transforms: the
// workpiece frame W seen from the A-axis frame K is Rot(X, A) Trans(Z, d)
// Rot(Z, C); the tool tip sits at Trans(X, Y, Z + d) in K. The pose in W is
// the inverse of the first applied to the second (general 4x4 inverse).
ToolPose elementary_forward(const Joints& q, double d) {
  auto rot = [](const Eigen::Vector3d& axis, double angle) {
    Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
    t.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    return t;
  };
  auto trans = [](double x, double y, double z) {
    Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
    t.topRightCorner<3, 1>() = Eigen::Vector3d(x, y, z);
    return t;
  };
  const Eigen::Matrix4d k_from_w =
      rot(Eigen::Vector3d::UnitX(), q.a) * trans(0, 0, d) * rot(Eigen::Vector3d::UnitZ(), q.c);
  const Eigen::Matrix4d tool_in_w = k_from_w.inverse() * trans(q.x, q.y, q.z + d);
  return {tool_in_w.topRightCorner<3, 1>(), tool_in_w.block<3, 1>(0, 2)};
}

TEST(TttrrForward, MatchesElementaryTransformsAndTheCorrectedDhChain) {
  const TttrrMachine m(test_machine());
  Rng rng(5);
  for (int i = 0; i < 2000; ++i) {
    const Joints q = random_joints(rng);
    const ToolPose p = m.forward(q);
    const ToolPose e = elementary_forward(q, m.options().offset_d);
    ASSERT_LT((p.position - e.position).cwiseAbs().maxCoeff(), kPositionTol);
    ASSERT_LT((p.orientation - e.orientation).cwiseAbs().maxCoeff(), kOrientationTol);
    const Eigen::Matrix4d t = dh_chain(m.dh_links(q));
    ASSERT_LT((p.position - t.topRightCorner<3, 1>()).cwiseAbs().maxCoeff(), kPositionTol);
    ASSERT_LT((p.orientation - t.block<3, 1>(0, 2)).cwiseAbs().maxCoeff(), kOrientationTol);
    // Seed 004 Eq. 4, first three lines: O = (sA sC, sA cC, cA).
    const Eigen::Vector3d eq4(std::sin(q.a) * std::sin(q.c), std::sin(q.a) * std::cos(q.c),
                              std::cos(q.a));
    ASSERT_LT((p.orientation - eq4).cwiseAbs().maxCoeff(), kOrientationTol);
  }
}

TEST(TttrrForward, HomePutsTheToolTipAtTheWorkpieceOrigin) {
  const TttrrMachine m(test_machine());
  const ToolPose p = m.forward({});
  EXPECT_LT(p.position.norm(), kPositionTol);
  EXPECT_LT((p.orientation - Eigen::Vector3d::UnitZ()).norm(), kOrientationTol);
}

// FK(IK(pose)) = pose on 1e5 random poses in the work volume, both branches.
// Poses: P uniform in a box, O uniform on the cap A in [1e-6, 80 deg]. The
// seed can be overridden with CNCLAB_IK_SEED to explore other poses.
TEST(TttrrInverse, RoundTripOnRandomPosesBothBranches) {
  const TttrrMachine m(test_machine());
  const char* seed_env = std::getenv("CNCLAB_IK_SEED");
  const std::uint64_t seed = seed_env ? std::strtoull(seed_env, nullptr, 10) : 20240607;
  SCOPED_TRACE("seed " + std::to_string(seed));
  Rng rng(seed);
  constexpr int kPoses = 100'000;
  double worst_p = 0, worst_o = 0;
  for (int i = 0; i < kPoses; ++i) {
    ToolPose pose;
    pose.position = {rng.uniform(-150, 150), rng.uniform(-150, 150), rng.uniform(-80, 120)};
    const double cos_tilt = rng.uniform(std::cos(80.0 * std::numbers::pi / 180.0), std::cos(1e-6));
    const double sin_tilt = std::sqrt(1 - cos_tilt * cos_tilt);
    const double azimuth = rng.uniform(-std::numbers::pi, std::numbers::pi);
    pose.orientation = {sin_tilt * std::cos(azimuth), sin_tilt * std::sin(azimuth), cos_tilt};
    const auto both = m.inverse_both(pose);
    ASSERT_TRUE(both[0] && both[1]);
    EXPECT_GT(both[0]->a, 0);
    EXPECT_LT(both[1]->a, 0);
    for (const auto& q : both) {
      const ToolPose back = m.forward(*q);
      worst_p = std::max(worst_p, (back.position - pose.position).cwiseAbs().maxCoeff());
      worst_o = std::max(worst_o, (back.orientation - pose.orientation).cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LT(worst_p, kPositionTol);
  EXPECT_LT(worst_o, kOrientationTol);
}

// IK(FK(q)) = q for joints inside the travel with A > 0 (the positive branch
// is the one that gave the pose), C in (-pi, pi].
TEST(TttrrInverse, RecoversTheJointsThatMadeThePose) {
  const TttrrMachine m(test_machine());
  Rng rng(9);
  for (int i = 0; i < 5000; ++i) {
    Joints q = random_joints(rng);
    q.a = std::abs(q.a) + 1e-3;
    const Joints r = m.inverse(m.forward(q), ABranch::positive);
    ASSERT_NEAR(r.a, q.a, 1e-12);
    ASSERT_NEAR(r.c, q.c, 1e-12);
    ASSERT_NEAR(r.x, q.x, 1e-9);
    ASSERT_NEAR(r.y, q.y, 1e-9);
    ASSERT_NEAR(r.z, q.z, 1e-9);
    // The other branch: A negated, C half a turn away.
    const Joints n = m.inverse(m.forward(q), ABranch::negative);
    ASSERT_NEAR(n.a, -q.a, 1e-12);
    ASSERT_NEAR(std::remainder(n.c - q.c - std::numbers::pi, 2 * std::numbers::pi), 0.0, 1e-12);
  }
}

TEST(TttrrInverse, CQuadrantsFollowAtan2) {
  const TttrrMachine m(test_machine());
  const double s = std::sin(0.5), c = std::cos(0.5);
  // O = (sA sC, sA cC, cA): C = 135 deg has sC > 0, cC < 0 (second quadrant).
  for (double deg : {30.0, 135.0, -45.0, -150.0, 180.0}) {
    const double cc = deg * std::numbers::pi / 180;
    ToolPose p;
    p.orientation = {s * std::sin(cc), s * std::cos(cc), c};
    const Joints q = m.inverse(p, ABranch::positive);
    EXPECT_NEAR(std::remainder(q.c - cc, 2 * std::numbers::pi), 0.0, 1e-12) << deg;
  }
}

TEST(TttrrInverse, SingularityKeepsThePreviousOrConfiguredC) {
  TttrrOptions o = test_machine();
  o.c_at_singularity = 0.25;
  const TttrrMachine m(o);
  ToolPose p;
  p.position = {10, 20, 30};
  const Joints configured = m.inverse(p, ABranch::positive);
  EXPECT_EQ(configured.a, 0.0);
  EXPECT_EQ(configured.c, 0.25);
  const Joints kept = m.inverse(p, ABranch::negative, 1.5);
  EXPECT_EQ(kept.c, 1.5);
  // Either way the pose is reproduced.
  for (const Joints& q : {configured, kept}) {
    EXPECT_LT((m.forward(q).position - p.position).norm(), kPositionTol);
  }
}

TEST(TttrrInverse, ChoosesTheTurnOfCClosestToThePrevious) {
  TttrrOptions o = test_machine();
  o.c = {-4 * std::numbers::pi, 4 * std::numbers::pi};
  const TttrrMachine m(o);
  const Joints q{1, 2, 3, 0.3, 0.2};
  const ToolPose p = m.forward(q);
  EXPECT_NEAR(m.inverse(p, ABranch::positive, 0.0).c, 0.2, 1e-12);
  EXPECT_NEAR(m.inverse(p, ABranch::positive, 2 * std::numbers::pi + 0.1).c,
              0.2 + 2 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(m.inverse(p, ABranch::positive, -5.0).c, 0.2 - 2 * std::numbers::pi, 1e-12);
}

template <class F>
std::string kinematics_error(F&& f) {
  return testing::error_message<KinematicsError>(std::forward<F>(f));
}

TEST(TttrrInverse, JointLimitsAndBadPosesAreClearErrors) {
  TttrrOptions o = test_machine();
  o.a = {-std::numbers::pi / 6, std::numbers::pi / 2};  // -30 .. 90 deg
  o.x = {-100, 100};
  const TttrrMachine m(o);
  ToolPose tilted;
  tilted.orientation = {0, std::sin(0.7), std::cos(0.7)};  // A = +-40.1 deg
  EXPECT_NO_THROW(m.inverse(tilted, ABranch::positive));
  const std::string a_msg = kinematics_error([&] { m.inverse(tilted, ABranch::negative); });
  EXPECT_NE(a_msg.find("A = -40.107 deg"), std::string::npos) << a_msg;
  EXPECT_NE(a_msg.find("[-30, 90] deg"), std::string::npos) << a_msg;
  const auto both = m.inverse_both(tilted);
  EXPECT_TRUE(both[0].has_value());
  EXPECT_FALSE(both[1].has_value());

  ToolPose far;
  far.position = {500, 0, 0};
  const std::string x_msg = kinematics_error([&] { m.inverse_both(far); });
  EXPECT_NE(x_msg.find("no inverse kinematics solution"), std::string::npos) << x_msg;
  EXPECT_NE(x_msg.find("X = 500 mm"), std::string::npos) << x_msg;

  ToolPose not_unit;
  not_unit.orientation = {0, 0, 1.1};
  EXPECT_NE(kinematics_error([&] { m.inverse(not_unit, ABranch::positive); }).find("unit vector"),
            std::string::npos);
  ToolPose nan_pose;
  nan_pose.position.x() = std::nan("");
  EXPECT_NE(kinematics_error([&] { m.inverse(nan_pose, ABranch::positive); }).find("not finite"),
            std::string::npos);
  EXPECT_THROW(m.check_limits({0, 0, 0, 2.0, 0}), KinematicsError);
}

// Central differences, step h: truncation error O(h^2 |f'''|) ~ 1e-8 for
// h = 1e-5 on these magnitudes, round-off ~ eps |f| / h ~ 1e-9.
TEST(TttrrJacobian, MatchesFiniteDifferences) {
  const TttrrMachine m(test_machine());
  Rng rng(17);
  constexpr double kH = 1e-5;
  for (int i = 0; i < 200; ++i) {
    const Joints q = random_joints(rng);
    const auto j = m.jacobian(q);
    for (int k = 0; k < 5; ++k) {
      Joints plus = q, minus = q;
      double* fields_plus[] = {&plus.x, &plus.y, &plus.z, &plus.a, &plus.c};
      double* fields_minus[] = {&minus.x, &minus.y, &minus.z, &minus.a, &minus.c};
      *fields_plus[k] += kH;
      *fields_minus[k] -= kH;
      const ToolPose fp = m.forward(plus), fm = m.forward(minus);
      Eigen::Matrix<double, 6, 1> fd;
      fd << (fp.position - fm.position) / (2 * kH), (fp.orientation - fm.orientation) / (2 * kH);
      ASSERT_LT((fd - j.col(k)).cwiseAbs().maxCoeff(), 1e-6) << "column " << k;
    }
  }
}

TEST(TttrrOptions, ValidateAndReadFromYamlInDegrees) {
  TttrrOptions bad = test_machine();
  bad.x = {5, -5};
  EXPECT_THROW(bad.validate(), OptionError);
  bad = test_machine();
  bad.a = {-4, 1};
  EXPECT_THROW(bad.validate(), OptionError);

  const ConfigDocument doc = ConfigDocument::parse(
      "machine:\n  offset_d: 42\n  limits: {a: [-30, 90], c: [0, 360], x: [-10, 10]}\n"
      "  c_at_singularity: 90\n",
      "test.yaml");
  const TttrrOptions o = read_tttrr_options(doc.root().section("machine"));
  EXPECT_EQ(o.offset_d, 42.0);
  EXPECT_NEAR(o.a.min, -std::numbers::pi / 6, 1e-15);
  EXPECT_NEAR(o.c.max, 2 * std::numbers::pi, 1e-15);
  EXPECT_NEAR(o.c_at_singularity, std::numbers::pi / 2, 1e-15);
  EXPECT_EQ(o.x.max, 10.0);
  // The YAML form reads back to the same options.
  const ConfigDocument again = ConfigDocument::parse(tttrr_options_yaml(o), "again.yaml");
  const TttrrOptions o2 = read_tttrr_options(again.root());
  EXPECT_NEAR(o2.a.min, o.a.min, 1e-15);
  EXPECT_NEAR(o2.c_at_singularity, o.c_at_singularity, 1e-15);
  EXPECT_EQ(o2.offset_d, o.offset_d);

  const ConfigDocument wrong =
      ConfigDocument::parse("machine:\n  limits: {a: [90, -30]}\n", "wrong.yaml");
  try {
    read_tttrr_options(wrong.root().section("machine"));
    FAIL();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("machine.limits.a"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace cnclab

namespace cnclab {
namespace {

// Every shipped machine file loads, validates and reaches the home pose.
TEST(TttrrOptions, ShippedMachineConfigsLoad) {
  int found = 0;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(CNCLAB_SOURCE_DIR) + "/configs/machines")) {
    if (entry.path().filename().string().rfind("tttrr_", 0) != 0) continue;
    const ConfigDocument doc = ConfigDocument::load(entry.path());
    const TttrrOptions o =
        read_tttrr_options(doc.root().section("dataset").section("options").section("machine"));
    EXPECT_NO_THROW(doc.check_all_consumed()) << entry.path();
    const TttrrMachine m(o);
    EXPECT_NO_THROW(m.inverse_both(ToolPose{})) << entry.path();
    ++found;
  }
  EXPECT_GE(found, 2);
}

}  // namespace
}  // namespace cnclab
