#pragma once
// The Gauss-Newton quantities of a residual objective, accumulated over row
// blocks: J^T J by a symmetric rank-k update per block (BLAS SYRK through
// Eigen's rankUpdate, nn/kernels.hpp: W^2 b / 2 multiply-adds per block of b
// rows, no N x W or N x W x W temporaries), J^T e and e^T e.
#include <Eigen/Core>

#include "cnclab/nn/kernel_table.hpp"
#include "cnclab/train/residual_objective.hpp"

namespace cnclab {

struct NormalEquations {
  Eigen::MatrixXd jtj;  // J^T J, lower triangle (the strict upper part is not used)
  Eigen::VectorXd jte;  // J^T e
  double sse = 0;       // e^T e
};

// Wall time spent in build() since construction (benchmarks report the
// J^T J step separately from the model's Jacobian evaluation).
struct NormalEquationTiming {
  double evaluate_seconds = 0;  // objective.evaluate (residuals and Jacobian blocks)
  double product_seconds = 0;   // rank updates J^T J and products J^T e
};

class NormalEquationBuilder {
 public:
  // block_rows: rows of J per rank update; 0 = about 8 MB of J per block.
  explicit NormalEquationBuilder(ResidualObjective& objective, Eigen::Index block_rows = 0);

  // Fills `out`; false (out unspecified) if any residual or Jacobian entry is
  // NaN or Inf.
  bool build(const Eigen::VectorXd& params, NormalEquations& out);
  // e^T e alone; +Inf if any residual is NaN or Inf.
  double sum_of_squares(const Eigen::VectorXd& params);

  Eigen::Index block_rows() const { return block_rows_; }
  const NormalEquationTiming& timing() const { return timing_; }

 private:
  ResidualObjective& objective_;
  const kernels::Table& kernels_;
  Eigen::Index block_rows_;
  Eigen::MatrixXd jacobian_;
  Eigen::VectorXd residuals_;
  NormalEquationTiming timing_;
};

}  // namespace cnclab
