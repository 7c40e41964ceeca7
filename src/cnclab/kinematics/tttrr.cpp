#include "cnclab/kinematics/tttrr.hpp"

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <numbers>

#include "cnclab/core/format.hpp"
#include "cnclab/core/units.hpp"

namespace cnclab {
namespace {

void check_range(const JointRange& r, const char* name) {
  if (!std::isfinite(r.min) || !std::isfinite(r.max) || !(r.min < r.max)) {
    throw OptionError(std::string("limits.") + name,
                      "[" + shortest_double(r.min) + ", " + shortest_double(r.max) + "]",
                      "must be finite with min < max");
  }
}

// A number for messages: 6 significant digits.
std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string range_text(const JointRange& r, bool angle) {
  const double f = angle ? kDegPerRad : 1.0;
  std::string text = "[";
  text += num(r.min * f);
  text += ", ";
  text += num(r.max * f);
  return text += angle ? "] deg" : "] mm";
}

}  // namespace

void TttrrOptions::validate() const {
  if (!std::isfinite(offset_d)) {
    throw OptionError("offset_d", shortest_double(offset_d), "must be a finite length in mm");
  }
  check_range(x, "x");
  check_range(y, "y");
  check_range(z, "z");
  check_range(a, "a");
  check_range(c, "c");
  if (a.min < -std::numbers::pi || a.max > std::numbers::pi) {
    throw OptionError("limits.a", range_text(a, true), "must lie inside [-180, 180] deg");
  }
  if (!(singular_tolerance > 0 && singular_tolerance < 1e-3)) {
    throw OptionError("singular_tolerance", shortest_double(singular_tolerance),
                      "must be in (0, 1e-3)");
  }
  if (!std::isfinite(c_at_singularity)) {
    throw OptionError("c_at_singularity", shortest_double(c_at_singularity), "must be finite");
  }
  if (!(unit_tolerance > 0 && unit_tolerance < 1e-3)) {
    throw OptionError("unit_tolerance", shortest_double(unit_tolerance), "must be in (0, 1e-3)");
  }
}

std::string to_string(ABranch b) {
  return b == ABranch::positive ? "positive" : "negative";
}

TttrrMachine::TttrrMachine(TttrrOptions options) : options_(options) {
  options_.validate();
}

ToolPose TttrrMachine::forward(const Joints& q) const {
  const double d = options_.offset_d;
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(q.a, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d rz = Eigen::AngleAxisd(q.c, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Vector3d tip_k(q.x, q.y, q.z + d);
  ToolPose pose;
  pose.position = rz.transpose() * (rx.transpose() * tip_k - d * Eigen::Vector3d::UnitZ());
  pose.orientation = rz.transpose() * rx.transpose() * Eigen::Vector3d::UnitZ();
  return pose;
}

void TttrrMachine::check_limits(const Joints& q) const {
  const auto check = [](double v, const JointRange& r, const char* axis, bool angle) {
    if (!r.contains(v)) {
      const double f = angle ? kDegPerRad : 1.0;
      throw KinematicsError(std::string("joint limit: ") + axis + " = " + num(v * f) +
                            (angle ? " deg" : " mm") + " is outside its travel " +
                            range_text(r, angle));
    }
  };
  check(q.x, options_.x, "X", false);
  check(q.y, options_.y, "Y", false);
  check(q.z, options_.z, "Z", false);
  check(q.a, options_.a, "A", true);
  check(q.c, options_.c, "C", true);
}

Joints TttrrMachine::inverse(const ToolPose& pose, ABranch branch,
                             std::optional<double> previous_c) const {
  const Eigen::Vector3d& o = pose.orientation;
  if (!pose.position.allFinite() || !o.allFinite()) {
    throw KinematicsError("unreachable pose: position or orientation is not finite");
  }
  if (std::abs(o.norm() - 1.0) > options_.unit_tolerance) {
    throw KinematicsError("unreachable pose: orientation (" + shortest_double(o.x()) + ", " +
                          shortest_double(o.y()) + ", " + shortest_double(o.z()) +
                          ") is not a unit vector (|O| = " + shortest_double(o.norm()) + ")");
  }
  const double sign = branch == ABranch::positive ? 1.0 : -1.0;
  const double s = std::hypot(o.x(), o.y());
  Joints q;
  q.a = sign * std::atan2(s, o.z());
  double c = 0;
  if (s <= options_.singular_tolerance) {
    // A = 0 (or 180 deg): the tool axis is the C axis and C is free.
    c = previous_c.value_or(options_.c_at_singularity);
  } else {
    c = std::atan2(sign * o.x(), sign * o.y());
  }
  // Choose the turn of C inside the travel, closest to the previous C.
  const double reference = previous_c.value_or(c);
  double best = c;
  bool found = false;
  for (int k = -3; k <= 3; ++k) {
    const double candidate = c + 2.0 * std::numbers::pi * k;
    if (!options_.c.contains(candidate)) continue;
    if (!found || std::abs(candidate - reference) < std::abs(best - reference)) best = candidate;
    found = true;
  }
  q.c = best;
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(q.a, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d rz = Eigen::AngleAxisd(q.c, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double d = options_.offset_d;
  const Eigen::Vector3d tip_k = rx * (rz * pose.position + d * Eigen::Vector3d::UnitZ());
  q.x = tip_k.x();
  q.y = tip_k.y();
  q.z = tip_k.z() - d;
  check_limits(q);
  return q;
}

std::array<std::optional<Joints>, 2> TttrrMachine::inverse_both(
    const ToolPose& pose, std::optional<double> previous_c) const {
  std::array<std::optional<Joints>, 2> out;
  std::string why;
  for (ABranch b : {ABranch::positive, ABranch::negative}) {
    try {
      out[b == ABranch::positive ? 0 : 1] = inverse(pose, b, previous_c);
    } catch (const KinematicsError& e) {
      why += std::string(why.empty() ? "" : "; ") + to_string(b) + " A branch: " + e.what();
    }
  }
  if (!out[0] && !out[1]) throw KinematicsError("no inverse kinematics solution: " + why);
  return out;
}

std::vector<DhLink> TttrrMachine::dh_links(const Joints& q) const {
  // W -> tool: Rz(-C) Tz(-d) Rx(-A) Trans(X, Y, Z + d), the inverse of the
  // W -> K map above, as four Eq. 1 links:
  //   (theta=-C, b=-d, a=0, alpha=-A): Rz(-C) Tz(-d) Rx(-A)
  //   (0, 0, X, 0): Tx(X)
  //   (pi/2, 0, Y, 0) then (-pi/2, Z + d, 0, 0): Ty(Y) Tz(Z + d)
  const double d = options_.offset_d;
  return {{-q.c, -d, 0.0, -q.a},
          {0.0, 0.0, q.x, 0.0},
          {std::numbers::pi / 2, 0.0, q.y, 0.0},
          {-std::numbers::pi / 2, q.z + d, 0.0, 0.0}};
}

Eigen::Matrix<double, 6, 5> TttrrMachine::jacobian(const Joints& q) const {
  // Multiplied out: with Zd = Z + d,
  //   Px = cC X + sC (cA Y + sA Zd),  Py = -sC X + cC (cA Y + sA Zd),
  //   Pz = -sA Y + cA Zd - d,         O = (sA sC, sA cC, cA).
  const double sa = std::sin(q.a), ca = std::cos(q.a), sc = std::sin(q.c), cc = std::cos(q.c);
  const double zd = q.z + options_.offset_d;
  const double u2 = ca * q.y + sa * zd, du2 = -sa * q.y + ca * zd;
  Eigen::Matrix<double, 6, 5> j = Eigen::Matrix<double, 6, 5>::Zero();
  j.col(0) << cc, -sc, 0, 0, 0, 0;
  j.col(1) << sc * ca, cc * ca, -sa, 0, 0, 0;
  j.col(2) << sc * sa, cc * sa, ca, 0, 0, 0;
  j.col(3) << sc * du2, cc * du2, -ca * q.y - sa * zd, ca * sc, ca * cc, -sa;
  j.col(4) << -sc * q.x + cc * u2, -cc * q.x - sc * u2, 0, sa * cc, -sa * sc, 0;
  return j;
}

}  // namespace cnclab
