#include "cnclab/kinematics/dh.hpp"

#include <cmath>

namespace cnclab {

Eigen::Matrix4d dh_transform(const DhLink& l) {
  // Rot(Z,theta) Trans(Z,b) Trans(X,a) Rot(X,alpha) multiplied out.
  const double ct = std::cos(l.theta), st = std::sin(l.theta);
  const double ca = std::cos(l.alpha), sa = std::sin(l.alpha);
  Eigen::Matrix4d t;
  t << ct, -st * ca, st * sa, l.a * ct,  //
      st, ct * ca, -ct * sa, l.a * st,   //
      0, sa, ca, l.b,                    //
      0, 0, 0, 1;
  return t;
}

Eigen::Matrix4d dh_chain(std::span<const DhLink> links) {
  Eigen::Matrix4d t = Eigen::Matrix4d::Identity();
  for (const DhLink& l : links) t = t * dh_transform(l);
  return t;
}

}  // namespace cnclab
