#include "cnclab/train/normal_equations.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "cnclab/core/error.hpp"
#include "cnclab/nn/kernels.hpp"

namespace cnclab {
namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

NormalEquationBuilder::NormalEquationBuilder(ResidualObjective& objective, Eigen::Index block_rows)
    : objective_(objective), kernels_(kernels::active()) {
  const Eigen::Index n = objective.num_residuals(), w = objective.num_parameters();
  const Eigen::Index g = objective.row_granularity();
  if (n < 1 || w < 1 || g < 1 || n % g != 0) {
    throw Error("least squares: " + std::to_string(n) + " residuals in groups of " +
                std::to_string(g) + ", " + std::to_string(w) + " parameters");
  }
  if (block_rows <= 0) {
    constexpr Eigen::Index kBlockDoubles = Eigen::Index{1} << 20;  // 8 MB of J
    block_rows = std::max<Eigen::Index>(256, kBlockDoubles / w);
  }
  block_rows = std::min(n, std::max(g, block_rows / g * g));
  block_rows_ = block_rows;
  jacobian_.resize(block_rows_, w);
  residuals_.resize(block_rows_);
}

bool NormalEquationBuilder::build(const Eigen::VectorXd& params, NormalEquations& out) {
  const Eigen::Index n = objective_.num_residuals(), w = objective_.num_parameters();
  out.jtj.setZero(w, w);
  out.jte.setZero(w);
  out.sse = 0;
  for (Eigen::Index first = 0; first < n; first += block_rows_) {
    const Eigen::Index count = std::min(block_rows_, n - first);
    if (count != jacobian_.rows()) jacobian_.resize(count, w);
    auto e = residuals_.head(count);
    const auto t0 = Clock::now();
    objective_.evaluate(params, first, count, e, &jacobian_);
    const auto t1 = Clock::now();
    if (!e.allFinite() || !jacobian_.allFinite()) return false;
    // J^T J (lower) += J_b^T J_b and J^T e += J_b^T e_b at this process's
    // instruction-set level (nn/kernels.hpp).
    kernels_.dsyrk(true, w, count, jacobian_.data(), jacobian_.outerStride(), out.jtj.data(),
                   out.jtj.outerStride());
    kernels_.dgemv(true, count, w, jacobian_.data(), jacobian_.outerStride(), e.data(),
                   out.jte.data());
    out.sse += e.squaredNorm();
    timing_.evaluate_seconds += std::chrono::duration<double>(t1 - t0).count();
    timing_.product_seconds += std::chrono::duration<double>(Clock::now() - t1).count();
  }
  if (jacobian_.rows() != block_rows_) jacobian_.resize(block_rows_, w);
  return std::isfinite(out.sse);
}

double NormalEquationBuilder::sum_of_squares(const Eigen::VectorXd& params) {
  const Eigen::Index n = objective_.num_residuals();
  double sse = 0;
  for (Eigen::Index first = 0; first < n; first += block_rows_) {
    const Eigen::Index count = std::min(block_rows_, n - first);
    auto e = residuals_.head(count);
    objective_.evaluate(params, first, count, e, nullptr);
    if (!e.allFinite()) return std::numeric_limits<double>::infinity();
    sse += e.squaredNorm();
  }
  return std::isfinite(sse) ? sse : std::numeric_limits<double>::infinity();
}

}  // namespace cnclab
