#pragma once
// Denavit-Hartenberg link transforms and chains, in the convention of seed 004
// Eq. (1):
//   ^{i-1}T_i = Rot(Z, theta_i) Trans(Z, b_i) Trans(X, a_i) Rot(X, alpha_i),
// angles in rad, lengths in mm. A chain is the product of its link transforms
// in order (seed 004 Eq. 2).
#include <Eigen/Core>
#include <span>

namespace cnclab {

struct DhLink {
  double theta = 0;  // rotation about the previous Z axis [rad]
  double b = 0;      // translation along the previous Z axis [mm]
  double a = 0;      // translation along the new X axis [mm]
  double alpha = 0;  // rotation about the new X axis [rad]
};

// The 4x4 homogeneous transform of one link (Eq. 1).
Eigen::Matrix4d dh_transform(const DhLink& link);

// The product T_1 T_2 ... T_n of the links' transforms (Eq. 2); identity for
// an empty chain.
Eigen::Matrix4d dh_chain(std::span<const DhLink> links);

}  // namespace cnclab
