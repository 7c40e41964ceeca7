#include "cnclab/motion/feedrate_nlp.hpp"

#include <algorithm>
#include <cmath>

namespace cnclab::feedrate_detail {
namespace {

constexpr double kInfinity = 1e19;  // Ipopt's default "no bound"
// Smallest interval duration (scaled time); keeps h away from 0 where the
// kinematic equalities degenerate. Real durations are ~1e-2 and larger.
constexpr double kMinDuration = 1e-9;

int v_index(int node) {
  return 4 * node;
}
int a_index(int node) {
  return 4 * node + 1;
}
int h_index(int interval) {
  return 4 * interval + 2;
}
int j_index(int interval) {
  return 4 * interval + 3;
}

// Largest v meeting the velocity ratios |vel_i| v <= 1 and the path-speed cap.
double velocity_bound(const NodeCoefficients& c) {
  double bound = std::min(kInfinity, c.v_cap);
  for (int i = 0; i < 2; ++i) {
    if (c.vel[i] != 0.0) bound = std::min(bound, 1.0 / std::abs(c.vel[i]));
  }
  return bound;
}

}  // namespace

FeedrateNlp::FeedrateNlp(std::vector<NodeCoefficients> nodes, WindowState start,
                         std::vector<double> guess, WindowState end)
    : nodes_(std::move(nodes)), start_(start), guess_(std::move(guess)), end_(end) {}

bool FeedrateNlp::get_nlp_info(Ipopt::Index& n, Ipopt::Index& m, Ipopt::Index& nnz_jac_g,
                               Ipopt::Index& nnz_h_lag, IndexStyleEnum& index_style) {
  const int N = intervals();
  n = 4 * N + 2;
  m = 3 * N + 2 * (N - 1) + 4 * N;
  nnz_jac_g = 13 * N + 4 * (N - 1) + 12 * N;
  nnz_h_lag = 2 * (N + 1) + 4 * N;
  index_style = C_STYLE;
  return true;
}

bool FeedrateNlp::get_bounds_info(Ipopt::Index n, Ipopt::Number* x_l, Ipopt::Number* x_u,
                                  Ipopt::Index m, Ipopt::Number* g_l, Ipopt::Number* g_u) {
  const int N = intervals();
  for (int k = 0; k <= N; ++k) {
    x_l[v_index(k)] = 0.0;
    x_u[v_index(k)] = velocity_bound(nodes_[k]);
    x_l[a_index(k)] = -kInfinity;
    x_u[a_index(k)] = kInfinity;
  }
  for (int k = 0; k < N; ++k) {
    x_l[h_index(k)] = kMinDuration;
    x_u[h_index(k)] = kInfinity;
    x_l[j_index(k)] = -kInfinity;
    x_u[j_index(k)] = kInfinity;
  }
  // Boundary states: the start is matched to the previous window (rest for
  // the first), the end is rest (or the given state, see the constructor).
  x_l[v_index(0)] = x_u[v_index(0)] = start_.v;
  x_l[a_index(0)] = x_u[a_index(0)] = start_.a;
  x_l[v_index(N)] = x_u[v_index(N)] = end_.v;
  x_l[a_index(N)] = x_u[a_index(N)] = end_.a;
  for (int r = 0; r < 3 * N; ++r) g_l[r] = g_u[r] = 0.0;
  for (int r = 3 * N; r < m; ++r) {
    g_l[r] = -1.0;
    g_u[r] = 1.0;
  }
  (void)n;
  return true;
}

bool FeedrateNlp::get_starting_point(Ipopt::Index n, bool init_x, Ipopt::Number* x, bool init_z,
                                     Ipopt::Number*, Ipopt::Number*, Ipopt::Index, bool init_lambda,
                                     Ipopt::Number*) {
  if (!init_x || init_z || init_lambda) return false;
  std::copy(guess_.begin(), guess_.begin() + n, x);
  return true;
}

bool FeedrateNlp::eval_f(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number& obj_value) {
  obj_value = 0.0;
  for (int k = 0; k < intervals(); ++k) obj_value += x[h_index(k)];
  return true;
}

bool FeedrateNlp::eval_grad_f(Ipopt::Index n, const Ipopt::Number*, bool, Ipopt::Number* grad_f) {
  std::fill(grad_f, grad_f + n, 0.0);
  for (int k = 0; k < intervals(); ++k) grad_f[h_index(k)] = 1.0;
  return true;
}

bool FeedrateNlp::eval_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index,
                         Ipopt::Number* g) {
  const int N = intervals();
  for (int k = 0; k < N; ++k) {
    const double v = x[v_index(k)], a = x[a_index(k)], h = x[h_index(k)], j = x[j_index(k)];
    g[3 * k] = v * h + a * h * h / 2 + j * h * h * h / 6 - (nodes_[k + 1].w - nodes_[k].w);
    g[3 * k + 1] = x[v_index(k + 1)] - v - a * h - j * h * h / 2;
    g[3 * k + 2] = x[a_index(k + 1)] - a - j * h;
  }
  for (int k = 1; k < N; ++k) {
    const double v = x[v_index(k)], a = x[a_index(k)];
    for (int i = 0; i < 2; ++i) {
      g[acc_row(k, i)] = nodes_[k].acc2[i] * v * v + nodes_[k].acc1[i] * a;
    }
  }
  for (int k = 0; k < N; ++k) {
    const double j = x[j_index(k)];
    for (int end = 0; end < 2; ++end) {
      const NodeCoefficients& c = nodes_[k + end];
      const double v = x[v_index(k + end)], a = x[a_index(k + end)];
      for (int i = 0; i < 2; ++i) {
        g[jerk_row(k, end, i)] = c.jerk3[i] * v * v * v + 3 * c.jerk2[i] * v * a + c.jerk1[i] * j;
      }
    }
  }
  return true;
}

bool FeedrateNlp::eval_jac_g(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Index, Ipopt::Index,
                             Ipopt::Index* iRow, Ipopt::Index* jCol, Ipopt::Number* values) {
  // One pass emits the entries in a fixed order: the structure on the first
  // call (values == nullptr), the values afterwards.
  int e = 0;
  auto emit = [&](int row, int col, auto value) {
    if (values == nullptr) {
      iRow[e] = row;
      jCol[e] = col;
    } else {
      values[e] = value();
    }
    ++e;
  };
  auto X = [&](int index) { return values == nullptr ? 0.0 : x[index]; };
  const int N = intervals();
  for (int k = 0; k < N; ++k) {
    const double v = X(v_index(k)), a = X(a_index(k)), h = X(h_index(k)), j = X(j_index(k));
    const int r = 3 * k;
    emit(r, v_index(k), [&] { return h; });
    emit(r, a_index(k), [&] { return h * h / 2; });
    emit(r, h_index(k), [&] { return v + a * h + j * h * h / 2; });
    emit(r, j_index(k), [&] { return h * h * h / 6; });
    emit(r + 1, v_index(k), [&] { return -1.0; });
    emit(r + 1, a_index(k), [&] { return -h; });
    emit(r + 1, h_index(k), [&] { return -a - j * h; });
    emit(r + 1, j_index(k), [&] { return -h * h / 2; });
    emit(r + 1, v_index(k + 1), [&] { return 1.0; });
    emit(r + 2, a_index(k), [&] { return -1.0; });
    emit(r + 2, h_index(k), [&] { return -j; });
    emit(r + 2, j_index(k), [&] { return -h; });
    emit(r + 2, a_index(k + 1), [&] { return 1.0; });
  }
  for (int k = 1; k < N; ++k) {
    const double v = X(v_index(k));
    for (int i = 0; i < 2; ++i) {
      emit(acc_row(k, i), v_index(k), [&] { return 2 * nodes_[k].acc2[i] * v; });
      emit(acc_row(k, i), a_index(k), [&] { return nodes_[k].acc1[i]; });
    }
  }
  for (int k = 0; k < N; ++k) {
    for (int end = 0; end < 2; ++end) {
      const NodeCoefficients& c = nodes_[k + end];
      const double v = X(v_index(k + end)), a = X(a_index(k + end));
      for (int i = 0; i < 2; ++i) {
        const int r = jerk_row(k, end, i);
        emit(r, v_index(k + end), [&] { return 3 * c.jerk3[i] * v * v + 3 * c.jerk2[i] * a; });
        emit(r, a_index(k + end), [&] { return 3 * c.jerk2[i] * v; });
        emit(r, j_index(k), [&] { return c.jerk1[i]; });
      }
    }
  }
  return true;
}

bool FeedrateNlp::eval_h(Ipopt::Index, const Ipopt::Number* x, bool, Ipopt::Number, Ipopt::Index,
                         const Ipopt::Number* lambda, bool, Ipopt::Index, Ipopt::Index* iRow,
                         Ipopt::Index* jCol, Ipopt::Number* values) {
  // Lower triangle. Node m: (v_m, v_m) at 2m, (a_m, v_m) at 2m+1; interval k:
  // (h, v_k), (h, a_k), (h, h), (j, h) at 2(N+1) + 4k + 0..3. The objective
  // is linear and contributes nothing.
  const int N = intervals();
  const int base = 2 * (N + 1);
  if (values == nullptr) {
    for (int m = 0; m <= N; ++m) {
      iRow[2 * m] = jCol[2 * m] = v_index(m);
      iRow[2 * m + 1] = a_index(m);
      jCol[2 * m + 1] = v_index(m);
    }
    for (int k = 0; k < N; ++k) {
      const int p = base + 4 * k;
      iRow[p] = h_index(k), jCol[p] = v_index(k);
      iRow[p + 1] = h_index(k), jCol[p + 1] = a_index(k);
      iRow[p + 2] = h_index(k), jCol[p + 2] = h_index(k);
      iRow[p + 3] = j_index(k), jCol[p + 3] = h_index(k);
    }
    return true;
  }
  std::fill(values, values + base + 4 * N, 0.0);
  for (int k = 0; k < N; ++k) {
    const double a = x[a_index(k)], h = x[h_index(k)], j = x[j_index(k)];
    const double l1 = lambda[3 * k], l2 = lambda[3 * k + 1], l3 = lambda[3 * k + 2];
    const int p = base + 4 * k;
    values[p] += l1;                                // d2 E1 / dh dv
    values[p + 1] += l1 * h - l2;                   // d2 / dh da
    values[p + 2] += l1 * (a + j * h) - l2 * j;     // d2 / dh2
    values[p + 3] += l1 * h * h / 2 - l2 * h - l3;  // d2 / dj dh
  }
  for (int m = 1; m < N; ++m) {
    for (int i = 0; i < 2; ++i) values[2 * m] += lambda[acc_row(m, i)] * 2 * nodes_[m].acc2[i];
  }
  for (int k = 0; k < N; ++k) {
    for (int end = 0; end < 2; ++end) {
      const int m = k + end;
      const NodeCoefficients& c = nodes_[m];
      const double v = x[v_index(m)];
      for (int i = 0; i < 2; ++i) {
        const double l = lambda[jerk_row(k, end, i)];
        values[2 * m] += l * 6 * c.jerk3[i] * v;
        values[2 * m + 1] += l * 3 * c.jerk2[i];
      }
    }
  }
  return true;
}

void FeedrateNlp::finalize_solution(Ipopt::SolverReturn, Ipopt::Index n, const Ipopt::Number* x,
                                    const Ipopt::Number*, const Ipopt::Number*, Ipopt::Index,
                                    const Ipopt::Number*, const Ipopt::Number*, Ipopt::Number,
                                    const Ipopt::IpoptData*, Ipopt::IpoptCalculatedQuantities*) {
  solution_.assign(x, x + n);
}

}  // namespace cnclab::feedrate_detail
