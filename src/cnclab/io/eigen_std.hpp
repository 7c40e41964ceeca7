#pragma once
// Copies between Eigen vectors and std::vector<double>, the form the HDF5
// layer reads and writes.
#include <Eigen/Core>
#include <vector>

namespace cnclab {

inline std::vector<double> to_std(const Eigen::VectorXd& v) {
  return {v.data(), v.data() + v.size()};
}

inline Eigen::VectorXd to_eigen(const std::vector<double>& v) {
  return Eigen::Map<const Eigen::VectorXd>(v.data(), static_cast<Eigen::Index>(v.size()));
}

}  // namespace cnclab
