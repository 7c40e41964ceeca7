#pragma once
// A matrix of independent standard normal entries, shared by the train tests
// (one definition: the unity build puts several test sources in one file).
#include <Eigen/Core>

#include "cnclab/core/rng.hpp"

namespace cnclab::test {

inline Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index cols, Rng& rng) {
  Eigen::MatrixXd m(rows, cols);
  for (Eigen::Index i = 0; i < m.size(); ++i) m.data()[i] = rng.normal();
  return m;
}

}  // namespace cnclab::test
