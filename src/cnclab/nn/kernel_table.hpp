#pragma once
// The hot kernels of one instruction-set level (core/isa.hpp) as a table of
// plain functions. Callers use nn/kernels.hpp; this header is the contract
// between it and the level translation units (kernels_level.cpp).
//
// How the levels stay apart (the one-definition rule): kernels_level.cpp is
// compiled once per level, with that level's flags (-mavx2 -mfma, -mavx512f
// ...) and, for v3 and v4, with -DEigen=cnclab_eigen_<level>, so that every
// Eigen template it instantiates lives in a namespace of its own. Without
// that, the linker would keep one copy of, say, Eigen's GEMM kernel for the
// whole program, and baseline code could end up running AVX-512 instructions
// (or the v4 kernels SSE2 ones). The level's own functions live in
// cnclab::kernels::<level>. So this header must not include Eigen or any
// header that does (a type named Eigen::X here would be another type there):
// pointers, sizes and plain structs only. The ctest kernel_symbols checks the
// v3 and v4 objects define nothing outside those two namespaces.
#include <cstddef>

namespace cnclab::kernels {

using Index = std::ptrdiff_t;

// Activations by number, in the order of cnclab::Activation (nn/activation.hpp).
enum class ActivationCode : int { relu = 0, tanh = 1, sigmoid = 2, linear = 3 };

// One block of rows of the closed-loop NARX Jacobian by RTRL (nn/narx.hpp),
// for steps s = first .. first + rows - 1 of the series:
//   S(s) = direct(s) + sum_{k=1..D_E} c_k(s) S(s - k),
//   direct(s) = [delta(s) x(s)^T (column-major, H x n), delta(s), a(s), 1],
//   c_k(s) = delta(s) . W1(:, D_V + k - 1),  delta = w2 .* f'(h),
// with S = 0 before the first step. `sens` is a row-major scratch of
// (D_E + rows) x W: on entry rows [0, D_E) hold S of the D_E steps before
// the block; the block's rows are computed into rows [D_E, D_E + rows),
// copied into the column-major Jacobian (rows first .. first + rows - 1,
// leading dimension ld_jacobian, `jacobian` pointing at row `first`), and
// the block's last D_E rows moved to the top for the next block.
struct RtrlBlock {
  Index rows = 0;                 // steps in this block
  Index hidden = 0;               // H
  Index input_delays = 0;         // D_V
  Index feedback_delays = 0;      // D_E
  const double* w1 = nullptr;     // H x (D_V + D_E), column-major (start of the parameters)
  const double* x = nullptr;      // (D_V + D_E) x rows regressors, column-major
  const double* a = nullptr;      // H x rows hidden activations f(h)
  const double* delta = nullptr;  // H x rows, w2 .* f'(h)
  double* sens = nullptr;         // (D_E + rows) x W, row-major, W = H (D_V + D_E) + 2 H + 1
  double* jacobian = nullptr;     // row `first` of the steps x W column-major Jacobian
  Index ld_jacobian = 0;          // its leading dimension (steps)
};

template <class T>
using GemmFn = void (*)(bool trans_a, bool trans_b, Index m, Index n, Index k, const T* a,
                        Index lda, const T* b, Index ldb, T beta, T* c, Index ldc);
template <class T>
using ActivationFn = void (*)(ActivationCode f, Index rows, Index cols, T* z, Index ld);
template <class T>
using DerivativeFn = void (*)(ActivationCode f, Index rows, Index cols, const T* a, Index lda,
                              T* delta, Index ld_delta);

struct Table {
  // C (m x n) = beta C + op(A) op(B), op(X) = X or X^T; column-major with
  // leading dimensions (BLAS xGEMM with alpha = 1; beta 0 ignores C's values).
  GemmFn<double> dgemm = nullptr;
  GemmFn<float> sgemm = nullptr;
  // Lower triangle of C (n x n) += A^T A for A k x n (trans), or A A^T for
  // A n x k; the strict upper part of C is not touched (BLAS DSYRK, uplo L).
  void (*dsyrk)(bool trans, Index n, Index k, const double* a, Index lda, double* c,
                Index ldc) = nullptr;
  // y += op(A) x, A m x n (BLAS DGEMV with alpha = beta = 1).
  void (*dgemv)(bool trans, Index m, Index n, const double* a, Index lda, const double* x,
                double* y) = nullptr;
  // z <- f(z), and delta *= f'(z) given a = f(z), element-wise over a
  // rows x cols column-major block.
  ActivationFn<double> dactivate = nullptr;
  ActivationFn<float> sactivate = nullptr;
  DerivativeFn<double> dderivative = nullptr;
  DerivativeFn<float> sderivative = nullptr;
  // Columns of an MLP layer's output Jacobian (nn/mlp.hpp, output_jacobian):
  // for i < out, j < in: J(k + n_out s, col0 + j out + i) = delta_t(s, i) a_t(s, j)
  // and J(k + n_out s, col0 + in out + i) = delta_t(s, i), s < batch.
  // delta_t (batch x out), a_t (batch x in) and J are column-major.
  void (*mlp_jacobian_columns)(Index batch, Index in, Index out, Index n_out, Index k,
                               const double* delta_t, const double* a_t, double* jacobian,
                               Index ld_jacobian, Index col0) = nullptr;
  void (*rtrl_block)(const RtrlBlock& block) = nullptr;
};

// One per compiled level (kernels_level.cpp); those not compiled are absent.
namespace baseline {
const Table& table();
}
namespace v3 {
const Table& table();
}
namespace v4 {
const Table& table();
}

}  // namespace cnclab::kernels
