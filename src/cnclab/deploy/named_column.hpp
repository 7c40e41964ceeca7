#pragma once
#include <Eigen/Core>
#include <string>

namespace cnclab {

// One named column of numbers with its unit, a value per sample: a column
// of a CSV table, an output of `cnclab predict`.
struct NamedColumn {
  std::string name;  // "e_x.closed_loop", "contour_error.closed_loop"
  std::string unit;  // "µm", "1" (dimensionless); "" where none is known
  Eigen::VectorXd values;
};

}  // namespace cnclab
