// The hot kernels (nn/kernels.hpp) at every instruction-set level this build
// has and this CPU runs: each against plain loops in long double (the
// textbook bound for a sum of k products: |c^ - c| <= k eps (|A||B|)_ij,
// eps = 2^-52), each level against the baseline within twice that bound,
// each level's result unchanged bit for bit when its inputs and outputs sit
// elsewhere in memory (what could otherwise differ between machines,
// kernels_level.cpp), and the baseline equal bit for bit to the plain Eigen
// expressions the code used before the kernels existed.
#include "cnclab/nn/kernels.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "cnclab/core/error.hpp"
#include "cnclab/core/rng.hpp"

namespace cnclab {
namespace {

using kernels::ActivationCode;
using kernels::Table;
constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr float kEpsF = std::numeric_limits<float>::epsilon();

std::vector<IsaLevel> runnable_levels() {
  std::vector<IsaLevel> levels;
  for (const IsaLevel l : compiled_isa_levels()) {
    if (cpu_supports(l)) levels.push_back(l);
  }
  return levels;
}

template <class T>
std::vector<T> random_values(std::size_t n, Rng& rng, double scale = 1.0) {
  std::vector<T> v(n);
  for (auto& x : v) x = static_cast<T>(scale * rng.normal());
  return v;
}

// Column-major element (i, j) of op(X) for X with leading dimension ld.
template <class T>
T element(const T* x, long ld, bool trans, long i, long j) {
  return trans ? x[j + i * ld] : x[i + j * ld];
}

struct GemmCase {
  bool ta, tb;
  long m, n, k;
  double beta;
};

// The inputs of one GEMM case, with leading dimensions above the minimum.
template <class T>
struct GemmData {
  GemmCase c;
  long lda, ldb, ldc;
  std::vector<T> a, b, c0;
  GemmData(GemmCase g, Rng& rng) : c(g) {
    lda = (g.ta ? g.k : g.m) + 3;
    ldb = (g.tb ? g.n : g.k) + 1;
    ldc = g.m + 2;
    a = random_values<T>(static_cast<std::size_t>(lda * (g.ta ? g.m : g.k)), rng);
    b = random_values<T>(static_cast<std::size_t>(ldb * (g.tb ? g.k : g.n)), rng);
    c0 = random_values<T>(static_cast<std::size_t>(ldc * g.n), rng);
  }
  // Runs t's GEMM with every buffer shifted by `shift` elements.
  std::vector<T> run(const Table& t, std::size_t shift = 0) const {
    std::vector<T> as(shift + a.size()), bs(shift + b.size()), cs(shift + c0.size());
    std::copy(a.begin(), a.end(), as.begin() + static_cast<long>(shift));
    std::copy(b.begin(), b.end(), bs.begin() + static_cast<long>(shift));
    std::copy(c0.begin(), c0.end(), cs.begin() + static_cast<long>(shift));
    const T beta = static_cast<T>(c.beta);
    if constexpr (std::is_same_v<T, double>) {
      t.dgemm(c.ta, c.tb, c.m, c.n, c.k, as.data() + shift, lda, bs.data() + shift, ldb, beta,
              cs.data() + shift, ldc);
    } else {
      t.sgemm(c.ta, c.tb, c.m, c.n, c.k, as.data() + shift, lda, bs.data() + shift, ldb, beta,
              cs.data() + shift, ldc);
    }
    return std::vector<T>(cs.begin() + static_cast<long>(shift), cs.end());
  }
  // (exact value in long double, sum of |terms|) of element (i, j).
  std::pair<long double, long double> reference(long i, long j) const {
    long double sum = c.beta == 0 ? 0.0L : static_cast<long double>(c.beta) * c0[i + j * ldc];
    long double abs = std::abs(sum);
    for (long l = 0; l < c.k; ++l) {
      const long double p = static_cast<long double>(element(a.data(), lda, c.ta, i, l)) *
                            element(b.data(), ldb, c.tb, l, j);
      sum += p;
      abs += std::abs(p);
    }
    return {sum, abs};
  }
};

const std::vector<GemmCase> kGemmCases = {
    // The shapes of the MLP products (forward W a, gradient delta a^T, back
    // W^T delta) at batch 1, 32 and 256, a tiny one (Eigen's coefficient-wise
    // path) and odd sizes.
    {false, false, 28, 1, 73, 0},
    {false, true, 28, 73, 32, 0},
    {true, false, 28, 32, 20, 0},
    {false, false, 20, 256, 28, 0},
    {true, true, 7, 5, 3, 0},
    {false, false, 3, 4, 5, 1},
    {true, false, 61, 37, 129, 1},
    {false, true, 33, 17, 65, 0.5},
    {true, true, 19, 23, 300, 1},
    // Small products with a depth of a few vector packets (rows + columns +
    // depth < 20: Eigen's coefficient-wise path, whose dot products start
    // at the first aligned address): a 4-8-6-1 network at batch 5.
    {false, false, 6, 5, 8, 0},
    {false, true, 6, 8, 5, 0},
    {true, false, 8, 5, 6, 0},
    {false, false, 3, 4, 12, 0}};

template <class T>
void check_gemm(double eps, double between_levels) {
  Rng rng(1);
  for (const GemmCase& g : kGemmCases) {
    const GemmData<T> data(g, rng);
    const std::vector<T> base = data.run(kernels::table_for(IsaLevel::baseline));
    for (const IsaLevel level : runnable_levels()) {
      const std::vector<T> got = data.run(kernels::table_for(level));
      const std::string where = std::string(to_string(level)) + " m " + std::to_string(g.m) +
                                " n " + std::to_string(g.n) + " k " + std::to_string(g.k);
      for (long j = 0; j < g.n; ++j) {
        for (long i = 0; i < g.m; ++i) {
          const auto [exact, abs] = data.reference(i, j);
          const double bound = static_cast<double>(g.k + 1) * eps * static_cast<double>(abs);
          const T x = got[static_cast<std::size_t>(i + j * data.ldc)];
          EXPECT_LE(std::abs(static_cast<long double>(x) - exact), bound)
              << where << " (" << i << ", " << j << ")";
          const T y = base[static_cast<std::size_t>(i + j * data.ldc)];
          EXPECT_LE(std::abs(static_cast<double>(x) - static_cast<double>(y)),
                    between_levels * bound)
              << where << " against the baseline";
        }
      }
      // Rows of C outside m (the leading-dimension padding) are not touched.
      for (long j = 0; j < g.n; ++j) {
        for (long i = g.m; i < data.ldc; ++i) {
          EXPECT_EQ(got[static_cast<std::size_t>(i + j * data.ldc)],
                    data.c0[static_cast<std::size_t>(i + j * data.ldc)]);
        }
      }
      for (std::size_t shift = 1; shift < 8; ++shift) {
        EXPECT_EQ(data.run(kernels::table_for(level), shift), got) << where << " shift " << shift;
      }
    }
  }
}

TEST(Kernels, GemmWithinTheSumBoundAtEveryLevelAndIndependentOfAddresses) {
  check_gemm<double>(kEps, 2.0);
  check_gemm<float>(kEpsF, 2.0);
}

TEST(Kernels, SyrkAndGemvWithinTheSumBoundAtEveryLevel) {
  Rng rng(2);
  for (const auto& shape : {std::pair<long, long>{121, 700}, {13, 5}, {1, 9}, {64, 64}}) {
    // Named copies, not a structured binding: the lambda below captures them
    // (clang before 16 cannot capture a structured binding).
    const long n = shape.first, k = shape.second;
    for (const bool trans : {true, false}) {
      // trans: A is k x n, C += A^T A; else A is n x k, C += A A^T.
      const long lda = (trans ? k : n) + 1, ldc = n + 2;
      const auto a = random_values<double>(static_cast<std::size_t>(lda * (trans ? n : k)), rng);
      const auto c0 = random_values<double>(static_cast<std::size_t>(ldc * n), rng);
      const auto run = [&](const Table& t, std::size_t shift) {
        std::vector<double> as(shift + a.size()), cs(shift + c0.size());
        std::copy(a.begin(), a.end(), as.begin() + static_cast<long>(shift));
        std::copy(c0.begin(), c0.end(), cs.begin() + static_cast<long>(shift));
        t.dsyrk(trans, n, k, as.data() + shift, lda, cs.data() + shift, ldc);
        return std::vector<double>(cs.begin() + static_cast<long>(shift), cs.end());
      };
      const std::vector<double> base = run(kernels::table_for(IsaLevel::baseline), 0);
      for (const IsaLevel level : runnable_levels()) {
        const std::vector<double> got = run(kernels::table_for(level), 0);
        for (long j = 0; j < n; ++j) {
          for (long i = 0; i < n; ++i) {
            const auto at = static_cast<std::size_t>(i + j * ldc);
            if (i < j) {  // strict upper triangle: untouched
              EXPECT_EQ(got[at], c0[at]);
              continue;
            }
            long double exact = c0[at], abs = std::abs(c0[at]);
            for (long l = 0; l < k; ++l) {
              const long double p = static_cast<long double>(element(a.data(), lda, trans, i, l)) *
                                    element(a.data(), lda, !trans, l, j);
              exact += p;
              abs += std::abs(p);
            }
            const double bound = static_cast<double>(k + 1) * kEps * static_cast<double>(abs);
            EXPECT_LE(std::abs(got[at] - exact), bound) << to_string(level);
            EXPECT_LE(std::abs(got[at] - base[at]), 2 * bound) << to_string(level);
          }
        }
        for (std::size_t shift = 1; shift < 8; ++shift) {
          EXPECT_EQ(run(kernels::table_for(level), shift), got) << to_string(level);
        }
      }
      // y += op(A) x with the same A.
      const long m = trans ? k : n, cols = trans ? n : k;  // A is m x cols either way
      const auto x = random_values<double>(static_cast<std::size_t>(trans ? m : cols), rng);
      const auto y0 = random_values<double>(static_cast<std::size_t>(trans ? cols : m), rng);
      for (const IsaLevel level : runnable_levels()) {
        std::vector<double> y = y0;
        kernels::table_for(level).dgemv(trans, m, cols, a.data(), lda, x.data(), y.data());
        for (std::size_t r = 0; r < y.size(); ++r) {
          long double exact = y0[r], abs = std::abs(y0[r]);
          for (std::size_t l = 0; l < x.size(); ++l) {
            const long double p =
                static_cast<long double>(trans ? a[l + r * static_cast<std::size_t>(lda)]
                                               : a[r + l * static_cast<std::size_t>(lda)]) *
                x[l];
            exact += p;
            abs += std::abs(p);
          }
          EXPECT_LE(std::abs(y[r] - exact),
                    static_cast<double>(x.size() + 1) * kEps * static_cast<double>(abs))
              << to_string(level);
        }
      }
    }
  }
}

// f and f'(given f) in long double.
long double reference_activation(ActivationCode f, long double z) {
  switch (f) {
    case ActivationCode::relu:
      return z > 0 ? z : 0;
    case ActivationCode::tanh:
      return std::tanh(z);
    case ActivationCode::sigmoid:
      return 1 / (1 + std::exp(-z));
    case ActivationCode::linear:
      return z;
  }
  return 0;
}
long double reference_derivative(ActivationCode f, long double a) {
  switch (f) {
    case ActivationCode::relu:
      return a > 0 ? 1 : 0;
    case ActivationCode::tanh:
      return 1 - a * a;
    case ActivationCode::sigmoid:
      return a * (1 - a);
    case ActivationCode::linear:
      return 1;
  }
  return 0;
}

// Activations within `ulps` units in the last place of the value (plus that
// much of 1 near zero), the derivative product within 4 of its terms'.
template <class T>
void check_activations(double ulps) {
  const double eps = std::numeric_limits<T>::epsilon();
  Rng rng(3);
  const long rows = 29, cols = 5, ld = 31;  // odd rows: every vector tail
  const auto z0 = random_values<T>(static_cast<std::size_t>(ld * cols), rng, 3.0);
  const auto d0 = random_values<T>(z0.size(), rng);
  for (const ActivationCode f : {ActivationCode::relu, ActivationCode::tanh,
                                 ActivationCode::sigmoid, ActivationCode::linear}) {
    const auto run = [&](const Table& t, std::size_t shift) {
      std::vector<T> z(shift + z0.size()), d(shift + d0.size());
      std::copy(z0.begin(), z0.end(), z.begin() + static_cast<long>(shift));
      std::copy(d0.begin(), d0.end(), d.begin() + static_cast<long>(shift));
      if constexpr (std::is_same_v<T, double>) {
        t.dactivate(f, rows, cols, z.data() + shift, ld);
        t.dderivative(f, rows, cols, z.data() + shift, ld, d.data() + shift, ld);
      } else {
        t.sactivate(f, rows, cols, z.data() + shift, ld);
        t.sderivative(f, rows, cols, z.data() + shift, ld, d.data() + shift, ld);
      }
      z.erase(z.begin(), z.begin() + static_cast<long>(shift));
      d.erase(d.begin(), d.begin() + static_cast<long>(shift));
      z.insert(z.end(), d.begin(), d.end());
      return z;  // f(z), then delta f'
    };
    for (const IsaLevel level : runnable_levels()) {
      const std::vector<T> got = run(kernels::table_for(level), 0);
      const std::string where =
          std::string(to_string(level)) + " activation " + std::to_string(static_cast<int>(f));
      for (long j = 0; j < cols; ++j) {
        for (long i = 0; i < ld; ++i) {
          const auto at = static_cast<std::size_t>(i + j * ld);
          const T a = got[at], d = got[z0.size() + at];
          if (i >= rows) {  // padding: untouched
            EXPECT_EQ(a, z0[at]);
            EXPECT_EQ(d, d0[at]);
            continue;
          }
          const long double fa = reference_activation(f, z0[at]);
          EXPECT_LE(std::abs(a - fa), ulps * eps * (std::abs(static_cast<double>(fa)) + 1e-3))
              << where;
          const long double fd = reference_derivative(f, a) * d0[at];
          EXPECT_LE(std::abs(d - fd), 4 * eps * (std::abs(static_cast<double>(d0[at])) + 1e-30))
              << where;
        }
      }
      for (std::size_t shift = 1; shift < 8; ++shift) {
        EXPECT_EQ(run(kernels::table_for(level), shift), got) << where << " shift " << shift;
      }
    }
  }
}

TEST(Kernels, ActivationsWithinStatedUlpsAtEveryLevelAndIndependentOfAddresses) {
  check_activations<double>(4);
  check_activations<float>(8);
}

TEST(Kernels, BaselineEqualsThePlainEigenExpressionsBitForBit) {
  const Table& t = kernels::table_for(IsaLevel::baseline);
  Rng rng(4);
  for (const auto [m, n, k] :
       {std::array<long, 3>{28, 1, 73}, {20, 256, 28}, {3, 4, 5}, {121, 121, 4000}}) {
    Eigen::MatrixXd a(m, k), b(k, n);
    for (long i = 0; i < a.size(); ++i) a.data()[i] = rng.normal();
    for (long i = 0; i < b.size(); ++i) b.data()[i] = rng.normal();
    Eigen::MatrixXd expected(m, n), got(m, n);
    expected.noalias() = a * b;
    kernels::multiply(t, a, false, b, false, got);
    EXPECT_EQ(got, expected);
    expected.noalias() = a.transpose() * a;
    got.resize(k, k);
    kernels::multiply(t, a, true, a, false, got);
    EXPECT_EQ(got, expected);
    // J^T J and J^T e as NormalEquationBuilder had them.
    Eigen::MatrixXd jtj = Eigen::MatrixXd::Zero(k, k), jtj_kernel = jtj;
    jtj.selfadjointView<Eigen::Lower>().rankUpdate(a.transpose());
    t.dsyrk(true, k, m, a.data(), a.outerStride(), jtj_kernel.data(), jtj_kernel.outerStride());
    EXPECT_EQ(jtj_kernel, jtj);
    const Eigen::VectorXd e = b.col(0).head(std::min(k, m)).replicate(1, 1);
    if (e.size() == m) {
      Eigen::VectorXd jte = Eigen::VectorXd::Zero(k), jte_kernel = jte;
      jte.noalias() += a.transpose() * e;
      t.dgemv(true, m, k, a.data(), a.outerStride(), e.data(), jte_kernel.data());
      EXPECT_EQ(jte_kernel, jte);
    }
  }
  // Activations as nn/activation.cpp had them: on an Eigen::Ref (outer
  // stride unknown at compile time, so Eigen vectorises column by column).
  Eigen::MatrixXd z(25, 7), delta(25, 7);
  for (long i = 0; i < z.size(); ++i) z.data()[i] = 2 * rng.normal();
  for (long i = 0; i < delta.size(); ++i) delta.data()[i] = rng.normal();
  Eigen::MatrixXd s = z, s_kernel = z;
  [](Eigen::Ref<Eigen::MatrixXd> r) { r = (1.0 + (-r.array()).exp()).inverse(); }(s);
  t.dactivate(ActivationCode::sigmoid, 25, 7, s_kernel.data(), 25);
  EXPECT_EQ(s_kernel, s);
  Eigen::MatrixXd d = delta, d_kernel = delta;
  [](const Eigen::Ref<const Eigen::MatrixXd>& a, Eigen::Ref<Eigen::MatrixXd> r) {
    r.array() *= a.array() * (1.0 - a.array());
  }(s, d);
  t.dderivative(ActivationCode::sigmoid, 25, 7, s.data(), 25, d_kernel.data(), 25);
  EXPECT_EQ(d_kernel, d);
}

// RTRL rows against the recursion of kernel_table.hpp in long double, over
// blocks of 5 (one shorter than the 3 feedback delays at the end).
TEST(Kernels, RtrlBlocksFollowTheRecursionAtEveryLevel) {
  const long h = 6, dv = 2, de = 3, n = dv + de, w = h * n + 2 * h + 1, steps = 17;
  Rng rng(5);
  const auto w1 = random_values<double>(static_cast<std::size_t>(h * n), rng, 0.2);
  const auto x = random_values<double>(static_cast<std::size_t>(n * steps), rng);
  const auto a = random_values<double>(static_cast<std::size_t>(h * steps), rng);
  const auto delta = random_values<double>(static_cast<std::size_t>(h * steps), rng, 0.5);
  // Reference S(s), steps x w, row by row.
  std::vector<long double> ref(static_cast<std::size_t>(steps * w), 0.0L);
  for (long s = 0; s < steps; ++s) {
    long double* row = ref.data() + s * w;
    for (long j = 0; j < n; ++j) {
      for (long i = 0; i < h; ++i)
        row[j * h + i] = static_cast<long double>(delta[s * h + i]) * x[s * n + j];
    }
    for (long i = 0; i < h; ++i) {
      row[h * n + i] = delta[s * h + i];
      row[h * n + h + i] = a[s * h + i];
    }
    row[h * n + 2 * h] = 1;
    for (long k = 1; k <= de && s - k >= 0; ++k) {
      long double c = 0;
      for (long i = 0; i < h; ++i)
        c += static_cast<long double>(delta[s * h + i]) * w1[(dv + k - 1) * h + i];
      for (long i = 0; i < w; ++i) row[i] += c * ref[(s - k) * w + i];
    }
  }
  const auto run = [&](const Table& t, long block) {
    std::vector<double> sens(static_cast<std::size_t>((de + block) * w), 0.0);
    std::vector<double> jac(static_cast<std::size_t>(steps * w), std::nan(""));
    for (long first = 0; first < steps; first += block) {
      kernels::RtrlBlock b;
      b.rows = std::min(block, steps - first);
      b.hidden = h;
      b.input_delays = dv;
      b.feedback_delays = de;
      b.w1 = w1.data();
      b.x = x.data() + first * n;
      b.a = a.data() + first * h;
      b.delta = delta.data() + first * h;
      b.sens = sens.data();
      b.jacobian = jac.data() + first;
      b.ld_jacobian = steps;
      t.rtrl_block(b);
    }
    return jac;
  };
  const std::vector<double> base = run(kernels::table_for(IsaLevel::baseline), 5);
  for (const IsaLevel level : runnable_levels()) {
    for (const long block : {5L, 2L, 17L}) {
      const std::vector<double> got = run(kernels::table_for(level), block);
      for (long s = 0; s < steps; ++s) {
        long double scale = 0;
        for (long i = 0; i < w; ++i) scale = std::max(scale, std::abs(ref[s * w + i]));
        for (long i = 0; i < w; ++i) {
          const double v = got[static_cast<std::size_t>(s + i * steps)];
          EXPECT_LE(std::abs(v - ref[s * w + i]), 1e-13 * static_cast<double>(scale))
              << to_string(level) << " block " << block << " step " << s << " column " << i;
          EXPECT_LE(std::abs(v - base[static_cast<std::size_t>(s + i * steps)]),
                    2e-13 * static_cast<double>(scale));
        }
      }
    }
  }
}

TEST(Kernels, MlpJacobianColumnsAreExactProductsAtEveryLevel) {
  const long batch = 9, in = 4, out = 3, n_out = 2, k = 1, col0 = 5;
  const long params = col0 + in * out + out + 2;
  Rng rng(6);
  const auto delta_t = random_values<double>(static_cast<std::size_t>(batch * out), rng);
  const auto a_t = random_values<double>(static_cast<std::size_t>(batch * in), rng);
  for (const IsaLevel level : runnable_levels()) {
    std::vector<double> jac(static_cast<std::size_t>(batch * n_out * params), -7.0);
    kernels::table_for(level).mlp_jacobian_columns(batch, in, out, n_out, k, delta_t.data(),
                                                   a_t.data(), jac.data(), batch * n_out, col0);
    for (long s = 0; s < batch; ++s) {
      for (long i = 0; i < out; ++i) {
        for (long j = 0; j < in; ++j) {
          EXPECT_EQ(
              jac[static_cast<std::size_t>(k + n_out * s + (col0 + j * out + i) * batch * n_out)],
              delta_t[static_cast<std::size_t>(s + i * batch)] *
                  a_t[static_cast<std::size_t>(s + j * batch)]);
        }
        EXPECT_EQ(
            jac[static_cast<std::size_t>(k + n_out * s + (col0 + in * out + i) * batch * n_out)],
            delta_t[static_cast<std::size_t>(s + i * batch)]);
      }
      EXPECT_EQ(jac[static_cast<std::size_t>(0 + n_out * s + col0 * batch * n_out)],
                -7.0);  // other output's rows
    }
  }
}

TEST(Kernels, TablesOfLevelsThisBuildOrCpuLacksAreConfigErrors) {
  for (const IsaLevel l : {IsaLevel::baseline, IsaLevel::v3, IsaLevel::v4, IsaLevel::native}) {
    const auto compiled = compiled_isa_levels();
    const bool usable =
        std::find(compiled.begin(), compiled.end(), l) != compiled.end() && cpu_supports(l);
    if (usable) {
      EXPECT_NO_THROW(kernels::table_for(l));
    } else {
      EXPECT_THROW(kernels::table_for(l), ConfigError) << to_string(l);
    }
  }
}

}  // namespace
}  // namespace cnclab
