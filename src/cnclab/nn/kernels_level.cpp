// The hot kernels of one instruction-set level (kernel_table.hpp), compiled
// once per level by nn/CMakeLists.txt with CNCLAB_KERNEL_LEVEL = baseline,
// v3 or v4, that level's flags, and for v3 and v4 -DEigen=cnclab_eigen_<level>
// (a renamed copy of Eigen: kernel_table.hpp says why).
//
// Bits: within a level a kernel's result must not depend on the machine. The
// one thing besides the code that could change it is where the data sit:
// Eigen's reductions (dot, sum) and its element-wise loops over dynamic-size
// unaligned maps start with a scalar part up to the first 16/32/64-byte
// boundary, so both the order of a sum and which function (scalar or
// vector tanh, exp) computes an element would follow the address, and the
// addresses of heap buffers follow the allocation history (a longer host
// name, say). So the v3 and v4 kernels use only Eigen's GEMM, GEMV and rank
// updates (which pack or load unaligned, whatever the address), explicit
// loops (sums in index order, std::fma where an update is fused), and
// element-wise functions on fixed-size chunks (no alignment split). The
// baseline kernels keep the expressions the code had before the kernels
// existed, so the baseline's results are those of earlier versions bit for
// bit (its 16-byte boundaries are where Eigen's allocator puts every buffer).
// tests/nn/kernels_test.cpp checks both: each level against the baseline
// within a stated bound, and each level's result unchanged under shifts of
// its inputs in memory.
#ifndef CNCLAB_KERNEL_LEVEL
#error "CNCLAB_KERNEL_LEVEL (baseline, v3 or v4) is set by nn/CMakeLists.txt"
#endif
#define CNCLAB_KERNEL_BASELINE_baseline 1
#define CNCLAB_KERNEL_IS_BASELINE_(level) CNCLAB_KERNEL_BASELINE_##level
#define CNCLAB_KERNEL_IS_BASELINE(level) CNCLAB_KERNEL_IS_BASELINE_(level)
#if CNCLAB_KERNEL_IS_BASELINE(CNCLAB_KERNEL_LEVEL) == 1
#define CNCLAB_KERNEL_BASELINE 1
#else
#define CNCLAB_KERNEL_BASELINE 0
// Eigen computes a product whose rows + columns + depth are below this
// threshold (20 by default) coefficient by coefficient, each coefficient a
// vectorised dot product that starts with a scalar part up to the first
// aligned address: the bits would follow where the buffers sit (a 6 x 8
// times 8 x 5 product at v3 differed between two identical training runs in
// one process). 0 sends every product through the GEMM kernel, which packs
// its operands and sums in index order. The renamed Eigen of v3 and v4
// (nn/CMakeLists.txt) keeps this setting to these translation units.
#define EIGEN_GEMM_TO_COEFFBASED_THRESHOLD 0
#endif

#include <Eigen/Core>
#include <cmath>

#include "cnclab/core/eigen_cache_sizes.hpp"
#include "cnclab/nn/kernel_table.hpp"

namespace cnclab::kernels::CNCLAB_KERNEL_LEVEL {
namespace {

constexpr bool kBaseline = CNCLAB_KERNEL_BASELINE == 1;

template <class T>
using Matrix = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
template <class T>
using ConstMap = Eigen::Map<const Matrix<T>, Eigen::Unaligned, Eigen::OuterStride<>>;
template <class T>
using MutMap = Eigen::Map<Matrix<T>, Eigen::Unaligned, Eigen::OuterStride<>>;
using ConstVector = Eigen::Map<const Eigen::VectorXd>;
using MutVector = Eigen::Map<Eigen::VectorXd>;

template <class T>
void gemm(bool trans_a, bool trans_b, Index m, Index n, Index k, const T* a, Index lda, const T* b,
          Index ldb, T beta, T* c, Index ldc) {
  MutMap<T> cm(c, m, n, Eigen::OuterStride<>(ldc));
  const ConstMap<T> am(a, trans_a ? k : m, trans_a ? m : k, Eigen::OuterStride<>(lda));
  const ConstMap<T> bm(b, trans_b ? n : k, trans_b ? k : n, Eigen::OuterStride<>(ldb));
  if (beta == T(0)) {
    if (!trans_a && !trans_b) cm.noalias() = am * bm;
    if (!trans_a && trans_b) cm.noalias() = am * bm.transpose();
    if (trans_a && !trans_b) cm.noalias() = am.transpose() * bm;
    if (trans_a && trans_b) cm.noalias() = am.transpose() * bm.transpose();
    return;
  }
  if (beta != T(1)) cm *= beta;
  if (!trans_a && !trans_b) cm.noalias() += am * bm;
  if (!trans_a && trans_b) cm.noalias() += am * bm.transpose();
  if (trans_a && !trans_b) cm.noalias() += am.transpose() * bm;
  if (trans_a && trans_b) cm.noalias() += am.transpose() * bm.transpose();
}

void dsyrk(bool trans, Index n, Index k, const double* a, Index lda, double* c, Index ldc) {
  MutMap<double> cm(c, n, n, Eigen::OuterStride<>(ldc));
  if (trans) {
    cm.selfadjointView<Eigen::Lower>().rankUpdate(
        ConstMap<double>(a, k, n, Eigen::OuterStride<>(lda)).transpose());
  } else {
    cm.selfadjointView<Eigen::Lower>().rankUpdate(
        ConstMap<double>(a, n, k, Eigen::OuterStride<>(lda)));
  }
}

void dgemv(bool trans, Index m, Index n, const double* a, Index lda, const double* x, double* y) {
  const ConstMap<double> am(a, m, n, Eigen::OuterStride<>(lda));
  if (trans) {
    MutVector(y, n).noalias() += am.transpose() * ConstVector(x, m);
  } else {
    MutVector(y, m).noalias() += am * ConstVector(x, n);
  }
}

// Element-wise f on a fixed-size chunk (whole vector packets, no alignment
// split): the same function computes every element wherever it sits.
constexpr Index kChunk = 64;
template <class T>
using Chunk = Eigen::Array<T, kChunk, 1>;

template <class T>
void activate_chunk(ActivationCode f, Chunk<T>& z) {
  switch (f) {
    case ActivationCode::relu:
      z = z.max(T(0));
      break;
    case ActivationCode::tanh:
      z = z.tanh();
      break;
    case ActivationCode::sigmoid:
      z = (T(1) + (-z).exp()).inverse();
      break;
    case ActivationCode::linear:
      break;
  }
}

template <class T>
void derivative_chunk(ActivationCode f, const Chunk<T>& a, Chunk<T>& delta) {
  switch (f) {
    case ActivationCode::relu:
      delta = (a > T(0)).select(delta, T(0));
      break;
    case ActivationCode::tanh:
      delta *= T(1) - a.square();
      break;
    case ActivationCode::sigmoid:
      delta *= a * (T(1) - a);
      break;
    case ActivationCode::linear:
      break;
  }
}

// The baseline's expressions (those of nn/activation.cpp before the kernels).
template <class T>
void activate_baseline(ActivationCode f, Eigen::Ref<Matrix<T>> z) {
  switch (f) {
    case ActivationCode::relu:
      z = z.cwiseMax(T(0));
      break;
    case ActivationCode::tanh:
      z = z.array().tanh();
      break;
    case ActivationCode::sigmoid:
      z = (T(1) + (-z.array()).exp()).inverse();
      break;
    case ActivationCode::linear:
      break;
  }
}

template <class T>
void derivative_baseline(ActivationCode f, const Eigen::Ref<const Matrix<T>>& a,
                         Eigen::Ref<Matrix<T>> delta) {
  switch (f) {
    case ActivationCode::relu:
      delta = (a.array() > T(0)).select(delta, T(0));
      break;
    case ActivationCode::tanh:
      delta.array() *= T(1) - a.array().square();
      break;
    case ActivationCode::sigmoid:
      delta.array() *= a.array() * (T(1) - a.array());
      break;
    case ActivationCode::linear:
      break;
  }
}

template <class T>
void activate(ActivationCode f, Index rows, Index cols, T* z, Index ld) {
  if (f == ActivationCode::linear || rows == 0 || cols == 0) return;
  if constexpr (kBaseline) {
    activate_baseline<T>(f, MutMap<T>(z, rows, cols, Eigen::OuterStride<>(ld)));
  } else {
    for (Index j = 0; j < cols; ++j) {
      T* col = z + j * ld;
      Index i = 0;
      for (; i + kChunk <= rows; i += kChunk) {
        Chunk<T> c = Eigen::Map<Chunk<T>>(col + i);
        activate_chunk(f, c);
        Eigen::Map<Chunk<T>>(col + i) = c;
      }
      if (i < rows) {  // the tail, zero-padded to a whole chunk
        Chunk<T> c = Chunk<T>::Zero();
        for (Index r = i; r < rows; ++r) c[r - i] = col[r];
        activate_chunk(f, c);
        for (Index r = i; r < rows; ++r) col[r] = c[r - i];
      }
    }
  }
}

template <class T>
void derivative(ActivationCode f, Index rows, Index cols, const T* a, Index lda, T* delta,
                Index ldd) {
  if (f == ActivationCode::linear || rows == 0 || cols == 0) return;
  if constexpr (kBaseline) {
    derivative_baseline<T>(f, ConstMap<T>(a, rows, cols, Eigen::OuterStride<>(lda)),
                           MutMap<T>(delta, rows, cols, Eigen::OuterStride<>(ldd)));
  } else {
    for (Index j = 0; j < cols; ++j) {
      const T* ac = a + j * lda;
      T* dc = delta + j * ldd;
      Index i = 0;
      for (; i + kChunk <= rows; i += kChunk) {
        const Chunk<T> ak = Eigen::Map<const Chunk<T>>(ac + i);
        Chunk<T> dk = Eigen::Map<Chunk<T>>(dc + i);
        derivative_chunk(f, ak, dk);
        Eigen::Map<Chunk<T>>(dc + i) = dk;
      }
      if (i < rows) {
        Chunk<T> ak = Chunk<T>::Zero(), dk = Chunk<T>::Zero();
        for (Index r = i; r < rows; ++r) {
          ak[r - i] = ac[r];
          dk[r - i] = dc[r];
        }
        derivative_chunk(f, ak, dk);
        for (Index r = i; r < rows; ++r) dc[r] = dk[r - i];
      }
    }
  }
}

void mlp_jacobian_columns(Index batch, Index in, Index out, Index n_out, Index k,
                          const double* delta_t, const double* a_t, double* jacobian,
                          Index ld_jacobian, Index col0) {
  // Products only (one rounding each): the same bits at every level.
  using Strided = Eigen::Map<Eigen::VectorXd, 0, Eigen::InnerStride<>>;
  for (Index j = 0; j < in; ++j) {
    const ConstVector aj(a_t + j * batch, batch);
    for (Index i = 0; i < out; ++i) {
      Strided col(jacobian + (col0 + j * out + i) * ld_jacobian + k, batch,
                  Eigen::InnerStride<>(n_out));
      col = ConstVector(delta_t + i * batch, batch).cwiseProduct(aj);
    }
  }
  for (Index i = 0; i < out; ++i) {
    Strided col(jacobian + (col0 + in * out + i) * ld_jacobian + k, batch,
                Eigen::InnerStride<>(n_out));
    col = ConstVector(delta_t + i * batch, batch);
  }
}

void rtrl_block(const RtrlBlock& b) {
  const Index h = b.hidden, dv = b.input_delays, de = b.feedback_delays, n = dv + de;
  const Index w = h * n + 2 * h + 1;
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Eigen::Map<RowMajor> sens(b.sens, de + b.rows, w);
  const ConstMap<double> w1(b.w1, h, n, Eigen::OuterStride<>(h));
  for (Index s = 0; s < b.rows; ++s) {
    const double* x = b.x + s * n;
    const double* a = b.a + s * h;
    const double* delta = b.delta + s * h;
    const Index r = de + s;
    if constexpr (kBaseline) {
      // The expressions of Narx::simulate_closed_loop before the kernels.
      const ConstVector d(delta, h);
      auto row = sens.row(r);
      for (Index j = 0; j < n; ++j) row.segment(j * h, h) = d.transpose() * x[j];
      row.segment(h * n, h) = d.transpose();
      row.segment(h * n + h, h) = ConstVector(a, h).transpose();
      row[h * n + 2 * h] = 1.0;
      for (Index k = 1; k <= de; ++k) row += d.dot(w1.col(dv + k - 1)) * sens.row(r - k);
    } else {
      double* row = b.sens + r * w;
      for (Index j = 0; j < n; ++j) {
        for (Index i = 0; i < h; ++i) row[j * h + i] = delta[i] * x[j];
      }
      for (Index i = 0; i < h; ++i) {
        row[h * n + i] = delta[i];
        row[h * n + h + i] = a[i];
      }
      row[h * n + 2 * h] = 1.0;
      for (Index k = 1; k <= de; ++k) {
        const double* w1k = b.w1 + (dv + k - 1) * h;
        double c = 0;
        for (Index i = 0; i < h; ++i) c = std::fma(delta[i], w1k[i], c);
        const double* prev = b.sens + (r - k) * w;
        for (Index i = 0; i < w; ++i) row[i] = std::fma(c, prev[i], row[i]);
      }
    }
  }
  Eigen::Map<Matrix<double>, Eigen::Unaligned, Eigen::OuterStride<>> jac(
      b.jacobian, b.rows, w, Eigen::OuterStride<>(b.ld_jacobian));
  jac = sens.middleRows(de, b.rows);
  // The window's last de rows (those of the block, or with a block shorter
  // than de also some before it) start the next block's window.
  sens.topRows(de) = sens.middleRows(b.rows, de).eval();
}

Table make_table() {
  Eigen::setCpuCacheSizes(kEigenL1CacheBytes, kEigenL2CacheBytes, kEigenL3CacheBytes);
  Table t;
  t.dgemm = gemm<double>;
  t.sgemm = gemm<float>;
  t.dsyrk = dsyrk;
  t.dgemv = dgemv;
  t.dactivate = activate<double>;
  t.sactivate = activate<float>;
  t.dderivative = derivative<double>;
  t.sderivative = derivative<float>;
  t.mlp_jacobian_columns = mlp_jacobian_columns;
  t.rtrl_block = rtrl_block;
  return t;
}

}  // namespace

const Table& table() {
  static const Table t = make_table();
  return t;
}

}  // namespace cnclab::kernels::CNCLAB_KERNEL_LEVEL
