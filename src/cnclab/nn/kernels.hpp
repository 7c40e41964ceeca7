#pragma once
// The hot numerical kernels at an instruction-set level (core/isa.hpp): the
// products of the MLP forward and backward passes and of its Jacobian, the
// J^T J / J J^T / J^T e builds of Levenberg-Marquardt, the NARX RTRL
// recursion, and the activations (kernel_table.hpp lists them). Code that
// runs them takes the table of this process's level, kernels::active();
// tests and benchmarks may take any level's, kernels::table_for().
#include <Eigen/Core>
#include <type_traits>

#include "cnclab/core/isa.hpp"
#include "cnclab/nn/kernel_table.hpp"

namespace cnclab::kernels {

// The kernels of `level`; ConfigError if this build lacks it or this CPU
// cannot run it.
const Table& table_for(IsaLevel level);

// The kernels of active_isa(), looked up once.
const Table& active();

// c = op(a) op(b), or c += op(a) op(b) with `accumulate`, through t's GEMM:
// a, b, c column-major Eigen objects with unit inner stride (a matrix, a map
// or a block of one; double or float), c already sized.
template <class A, class B, class C>
void multiply(const Table& t, const A& a, bool trans_a, const B& b, bool trans_b, C&& c,
              bool accumulate = false) {
  using T = typename std::decay_t<C>::Scalar;
  const Index k = trans_a ? a.rows() : a.cols();
  const T beta = accumulate ? T(1) : T(0);
  if constexpr (std::is_same_v<T, double>) {
    t.dgemm(trans_a, trans_b, c.rows(), c.cols(), k, a.data(), a.outerStride(), b.data(),
            b.outerStride(), beta, c.data(), c.outerStride());
  } else {
    t.sgemm(trans_a, trans_b, c.rows(), c.cols(), k, a.data(), a.outerStride(), b.data(),
            b.outerStride(), beta, c.data(), c.outerStride());
  }
}

}  // namespace cnclab::kernels
