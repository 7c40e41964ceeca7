#pragma once
// The five-axis TTTRR machine seed 004 describes (Sec. 2, Figs. 1-2): table
// moving in X and Y, head moving in Z, table tilting about X (A) and a rotary
// table about its own normal on the tilting table (C). docs/kinematics.md has
// the frame sketch.
//
// Seed 004's D-H table (Table 1) does not describe this machine: multiplied
// out with Eq. 1 its A and C enter only as (A - C), and Eqs. 3 and 4 disagree
// with each other (tests/kinematics/dh_test.cpp shows both). The model here is
// built from the description instead, with Eq. 4's orientation lines kept:
//
//   frames: W = workpiece frame on the C table (origin on the C axis, d above
//   the A axis); K = the A-axis frame (origin on the A axis, axes parallel to
//   the machine axes, moving with the X/Y table). At home (all joints 0) the
//   tool tip is at the origin of W (Sec. 2: "the origin of tool holder frame G
//   is coincident with the workpiece frame P").
//     point in W -> K:  p_K = Rx(A) (Rz(C) p_W + d e_z)
//     tool tip in K:    t_K = (X, Y, Z + d);  tool axis in K: e_z
//   forward kinematics (joints -> pose in W):
//     P = Rz(C)^T (Rx(A)^T (X, Y, Z + d) - d e_z)
//     O = Rz(C)^T Rx(A)^T e_z = (sin A sin C, sin A cos C, cos A)   (Eq. 4)
//   inverse kinematics (pose -> joints), O a unit vector:
//     A = +-atan2(sqrt(Oi^2 + Oj^2), Ok)     (= +-arccos(Ok), Eq. 5, but
//                                             well conditioned near A = 0)
//     C = atan2(Oi, Oj) for A > 0, atan2(-Oi, -Oj) for A < 0
//     (X, Y, Z + d) = Rx(A) (Rz(C) P + d e_z)
// At A = 0 the tool axis is the C axis: C is free (kept at the previous C or
// the configured one).
#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/kinematics/dh.hpp"

namespace cnclab {

// A pose the machine cannot reach (joint limits, bad orientation vector).
class KinematicsError : public Error {
 public:
  using Error::Error;
};

// Machine axis values: X, Y, Z in mm, A and C in rad.
struct Joints {
  double x = 0, y = 0, z = 0, a = 0, c = 0;
};

// Tool tip position P [mm] and tool axis direction O (unit, pointing from the
// tip into the spindle), both in the workpiece frame W.
struct ToolPose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d orientation = Eigen::Vector3d::UnitZ();
};

struct JointRange {
  double min = 0, max = 0;  // inclusive; mm or rad
  bool contains(double v) const { return v >= min && v <= max; }
};

struct TttrrOptions {
  // d: distance from the A axis to the workpiece origin along the C axis [mm]
  // (seed 004 Table 1's d; its value is not given, ours is a parameter).
  double offset_d = 100.0;
  // Travel of each axis. A and C in rad (configs give degrees). C's range may
  // span more than one turn: IK picks the turn closest to the previous C.
  JointRange x{-400.0, 400.0}, y{-300.0, 300.0}, z{-300.0, 300.0};
  JointRange a{-1.9198621771937625, 1.9198621771937625};  // +-110 deg
  JointRange c{-3.141592653589793, 3.141592653589793};    // +-180 deg
  // |sin A| at or below this is the A = 0 singularity (C free) [1]
  double singular_tolerance = 1e-12;
  // C used at the singularity when the caller gives no previous C [rad]
  double c_at_singularity = 0.0;
  // Largest accepted | |O| - 1 | of a pose's orientation vector [1]
  double unit_tolerance = 1e-9;

  // Finite values, min < max, tolerances in (0, 1e-3), A range inside
  // [-pi, pi].
  void validate() const;
};

enum class ABranch { positive, negative };  // sign of A in the IK (Eq. 5's +-)
std::string to_string(ABranch b);

class TttrrMachine {
 public:
  explicit TttrrMachine(TttrrOptions options);  // validates

  const TttrrOptions& options() const { return options_; }

  // Joints -> pose in W (no limit check: any joint values are evaluated).
  ToolPose forward(const Joints& q) const;

  // Pose -> joints on one A branch. previous_c: the C of the previous pose
  // (used at the singularity and to choose among turns of C). Throws
  // KinematicsError if the orientation is not a unit vector or the solution
  // violates a joint limit (the message names the axis, value and range).
  Joints inverse(const ToolPose& pose, ABranch branch,
                 std::optional<double> previous_c = std::nullopt) const;

  // Both branches; a branch that violates a limit is absent. Throws
  // KinematicsError naming both reasons when neither is reachable.
  std::array<std::optional<Joints>, 2> inverse_both(
      const ToolPose& pose, std::optional<double> previous_c = std::nullopt) const;

  // Throws KinematicsError for the first axis outside its range.
  void check_limits(const Joints& q) const;

  // The same machine as a chain of Eq. 1 links (W -> tool tip): a corrected
  // D-H description, evaluated by dh_chain(); tests compare it with forward().
  std::vector<DhLink> dh_links(const Joints& q) const;

  // d(P, O)/d(X, Y, Z, A, C): rows Px, Py, Pz, Oi, Oj, Ok; columns X, Y, Z, A, C.
  Eigen::Matrix<double, 6, 5> jacobian(const Joints& q) const;

 private:
  TttrrOptions options_;
};

}  // namespace cnclab
