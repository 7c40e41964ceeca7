#pragma once
// A least-squares objective for Levenberg-Marquardt trainers: residuals
// e(w) in R^N over a flat parameter vector w in R^W and their Jacobian
// J(i, j) = de_i / dw_j, evaluated in blocks of rows so that no trainer ever
// needs all of J at once (the Ceres CostFunction split: the model evaluates,
// the solver solves).
#include <Eigen/Core>
#include <cstddef>

namespace cnclab {

class ResidualObjective {
 public:
  virtual ~ResidualObjective() = default;
  virtual Eigen::Index num_residuals() const = 0;   // N
  virtual Eigen::Index num_parameters() const = 0;  // W
  // Blocks start and end at multiples of this (e.g. the outputs of one
  // sample); num_residuals() is a multiple of it.
  virtual Eigen::Index row_granularity() const { return 1; }
  // Residual rows [first, first + count): e into `residuals` (size count)
  // and, if `jacobian` is not null, J into it (already sized count x W).
  virtual void evaluate(const Eigen::VectorXd& params, Eigen::Index first, Eigen::Index count,
                        Eigen::Ref<Eigen::VectorXd> residuals, Eigen::MatrixXd* jacobian) = 0;
};

}  // namespace cnclab
