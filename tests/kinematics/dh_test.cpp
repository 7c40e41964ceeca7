// The generic D-H evaluator against elementary transforms, and seed 004's
// printed D-H table (Table 1) and Eqs. 3-4 evaluated: the defects the issue
// states, kept reproducible.
#include "cnclab/kinematics/dh.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <vector>

#include "cnclab/core/rng.hpp"

namespace cnclab {
namespace {

constexpr double kTol = 1e-12;

Eigen::Matrix4d rot(const Eigen::Vector3d& axis, double angle) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
  return t;
}
Eigen::Matrix4d trans(const Eigen::Vector3d& v) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  t.topRightCorner<3, 1>() = v;
  return t;
}

TEST(DhTransform, EqualsTheProductOfEq1sElementaryTransforms) {
  Rng rng(1);
  for (int i = 0; i < 100; ++i) {
    const DhLink l{rng.uniform(-4, 4), rng.uniform(-50, 50), rng.uniform(-50, 50),
                   rng.uniform(-4, 4)};
    const Eigen::Matrix4d expected =
        rot(Eigen::Vector3d::UnitZ(), l.theta) * trans(l.b * Eigen::Vector3d::UnitZ()) *
        trans(l.a * Eigen::Vector3d::UnitX()) * rot(Eigen::Vector3d::UnitX(), l.alpha);
    ASSERT_LT((dh_transform(l) - expected).cwiseAbs().maxCoeff(), kTol);
  }
}

TEST(DhChain, MultipliesInOrderAndEmptyIsIdentity) {
  const std::vector<DhLink> links = {{0.3, 1, 2, 0.4}, {-0.7, 3, -1, 1.1}};
  EXPECT_LT((dh_chain(links) - dh_transform(links[0]) * dh_transform(links[1])).norm(), kTol);
  EXPECT_LT((dh_chain({}) - Eigen::Matrix4d::Identity()).norm(), 0.0 + kTol);
}

// Seed 004 Table 1, rows pT1 .. 5Tt: (theta, a, b, alpha) as printed.
std::vector<DhLink> table1(double x, double y, double z, double a, double c, double d) {
  return {{std::numbers::pi / 2, 0, 0, std::numbers::pi},
          {c, d, 0, std::numbers::pi},
          {a, 0, 0, 0},
          {-std::numbers::pi / 2, x, 0, std::numbers::pi / 2},
          {std::numbers::pi / 2, y, 0, std::numbers::pi / 2},
          {std::numbers::pi, z + d, 0, 0}};
}

// Multiplied out, Table 1's A and C enter only as (A - C): shifting both by
// the same delta leaves pTt unchanged, while changing either alone does not.
// Two rotations about parallel axes: not a five-axis machine.
TEST(Seed004Table1, AAndCEnterOnlyAsTheirDifference) {
  Rng rng(4);
  for (int i = 0; i < 200; ++i) {
    const double x = rng.uniform(-100, 100), y = rng.uniform(-100, 100), z = rng.uniform(-100, 100);
    const double a = rng.uniform(-2, 2), c = rng.uniform(-3, 3), d = rng.uniform(10, 200);
    const double delta = rng.uniform(-3, 3);
    const Eigen::Matrix4d t = dh_chain(table1(x, y, z, a, c, d));
    const Eigen::Matrix4d shifted = dh_chain(table1(x, y, z, a + delta, c + delta, d));
    ASSERT_LT((t - shifted).cwiseAbs().maxCoeff(), 1e-10);
    if (std::abs(std::sin(delta / 2)) > 0.1) {
      ASSERT_GT((t - dh_chain(table1(x, y, z, a + delta, c, d))).cwiseAbs().maxCoeff(), 1e-3);
    }
    // The tool's tilt against the workpiece Z axis (z component of the third
    // column) does not depend on A or C at all: nothing tilts.
    ASSERT_NEAR(t(2, 2), dh_chain(table1(x, y, z, 0, 0, d))(2, 2), 1e-12);
  }
}

// Eq. 3 (the printed pTt) and Eq. 4 (the printed forward kinematics) as
// transcribed; they should agree on the position and do not.
Eigen::Vector3d eq3_position(double x, double y, double z, double a, double c, double d) {
  return {-x * std::cos(c) - y * std::cos(a) * std::sin(c) + (z + d) * std::sin(a) * std::sin(c),
          x * std::sin(c) - y * std::cos(a) * std::cos(c) + (z + d) * std::sin(a) * std::cos(a),
          y * std::sin(a) + (z + d) * std::cos(a) - d};
}
Eigen::Vector3d eq4_position(double x, double y, double z, double a, double c, double d) {
  return {-x * std::sin(c) - y * std::cos(a) * std::sin(c) + (z + d) * std::sin(a) * std::cos(c),
          x * std::sin(c) - y * std::cos(a) * std::cos(c) + (z + d) * std::sin(a) * std::cos(c),
          y * std::sin(a) + (z + d) * std::cos(a)};
}

TEST(Seed004Equations, Eq3AndEq4Disagree) {
  const double x = 10, y = 20, z = 30, a = 0.4, c = 0.7, d = 50;
  const Eigen::Vector3d p3 = eq3_position(x, y, z, a, c, d);
  const Eigen::Vector3d p4 = eq4_position(x, y, z, a, c, d);
  // Every coordinate differs: Px (cos C vs sin C terms), Py (cos A vs cos C),
  // Pz (the -d).
  for (int i = 0; i < 3; ++i) EXPECT_GT(std::abs(p3[i] - p4[i]), 1.0) << "coordinate " << i;
  EXPECT_NEAR(p3.z() - p4.z(), -d, 1e-12);
  // Eq. 3's rotation part is not even a rotation (columns not orthonormal):
  // its first column is (cos C, -sin A, 0).
  const Eigen::Vector3d col1(std::cos(c), -std::sin(a), 0);
  EXPECT_GT(std::abs(col1.norm() - 1.0), 0.01);
  // Nor does Table 1 give either: its position differs from both.
  const Eigen::Vector3d p1 = dh_chain(table1(x, y, z, a, c, d)).topRightCorner<3, 1>();
  EXPECT_GT((p1 - p3).norm(), 1.0);
  EXPECT_GT((p1 - p4).norm(), 1.0);
}

}  // namespace
}  // namespace cnclab
