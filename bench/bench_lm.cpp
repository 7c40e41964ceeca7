// One Levenberg-Marquardt iteration, single thread, on
//   (a) an 85,000 x 121 Jacobian (the size of seed 002's open-loop NARX
//       problem; a stored dense J, so only the solver's work is timed), and
//   (b) the seed-000 network 73-28-20-1 ReLU on 13,860 samples (Jacobian by
//       per-sample backpropagation, 2,673 parameters),
//   (c) seed 002's NARX 12/4 on 86,000 steps, open and closed loop (RTRL),
// with the J^T J step's GFLOP/s (N W (W + 1) flops for the symmetric rank
// updates) against Eigen's dense GEMM rate measured in the same run.
//
//   cnclab_bench_lm iteration [REPEATS]   the timings above (medians)
//   cnclab_bench_lm prepare DIR           writes (b)'s data and initial weights
//                                         for scripts/bench_lm_scipy.py
//   cnclab_bench_lm race DIR TARGET_SSE   LM on (b) until SSE <= TARGET_SSE
//   cnclab_bench_lm gram [REPEATS]        J^T J of (c)'s closed-loop Jacobian
//                                         at every instruction-set level this
//                                         CPU runs, beside that level's Eigen
//                                         GEMM rate (target at v4: GEMM /
//                                         J^T J <= 1.3)
//   cnclab_bench_lm forms [EPOCHS]        trainbr on the step-error MLP
//                                         73-32-16-1 (2,913 weights, 936
//                                         samples): the P x P primal with one
//                                         Cholesky per mu trial (the method
//                                         before the dual form) against the
//                                         automatic form (N x N dual,
//                                         spectral), seconds per epoch and
//                                         the largest relative difference
// scripts/bench_lm runs all three beside scipy.optimize.least_squares(method='lm').
#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "cnclab/core/isa.hpp"
#include "cnclab/core/rng.hpp"
#include "cnclab/nn/kernels.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/mlp_residuals.hpp"
#include "cnclab/train/narx_training.hpp"
#include "cnclab/train/normal_equations.hpp"
#include "cnclab/train/trainbr.hpp"

namespace {
using namespace cnclab;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// A stored dense Jacobian: residuals e = J w - t.
class DenseResiduals : public ResidualObjective {
 public:
  DenseResiduals(Eigen::MatrixXd j, Eigen::VectorXd t) : j_(std::move(j)), t_(std::move(t)) {}
  Eigen::Index num_residuals() const override { return j_.rows(); }
  Eigen::Index num_parameters() const override { return j_.cols(); }
  void evaluate(const Eigen::VectorXd& w, Eigen::Index first, Eigen::Index count,
                Eigen::Ref<Eigen::VectorXd> e, Eigen::MatrixXd* jacobian) override {
    e.noalias() = j_.middleRows(first, count) * w;
    e -= t_.segment(first, count);
    if (jacobian) *jacobian = j_.middleRows(first, count);
  }

 private:
  Eigen::MatrixXd j_;
  Eigen::VectorXd t_;
};

// Eigen GEMM C = A B, n x n, in GFLOP/s (2 n^3 flops).
double gemm_gflops(int repeats) {
  const Eigen::Index n = 1024;
  Rng rng(1);
  Eigen::MatrixXd a(n, n), b(n, n), c(n, n);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = rng.normal();
  for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = rng.normal();
  std::vector<double> rates;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    c.noalias() = a * b;
    rates.push_back(2.0 * n * n * n / seconds_since(t0) / 1e9);
  }
  if (!c.allFinite()) std::abort();
  return median(rates);
}

struct IterationTimes {
  double evaluate, product, solve, trial;
};

// The work of one LM iteration: normal equations at w, one Cholesky solve of
// (J^T J + mu I) dw = -J^T e, the sum of squares at w + dw.
IterationTimes time_iteration(ResidualObjective& objective, const Eigen::VectorXd& w, int repeats) {
  NormalEquationBuilder builder(objective);
  NormalEquations ne;
  std::vector<double> evaluate, product, solve, trial;
  for (int r = 0; r < repeats; ++r) {
    const NormalEquationTiming before = builder.timing();
    if (!builder.build(w, ne)) std::abort();
    evaluate.push_back(builder.timing().evaluate_seconds - before.evaluate_seconds);
    product.push_back(builder.timing().product_seconds - before.product_seconds);
    auto t0 = Clock::now();
    Eigen::MatrixXd damped = ne.jtj;
    damped.diagonal().array() += 1e-3;
    const Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(damped);
    const Eigen::VectorXd step = llt.solve(-ne.jte);
    solve.push_back(seconds_since(t0));
    t0 = Clock::now();
    const double sse = builder.sum_of_squares(w + step);
    trial.push_back(seconds_since(t0));
    if (!std::isfinite(sse)) std::abort();
  }
  return {median(evaluate), median(product), median(solve), median(trial)};
}

void report(const char* name, Eigen::Index n, Eigen::Index w, const IterationTimes& t,
            double gemm) {
  const double flops = static_cast<double>(n) * static_cast<double>(w) * (w + 1.0);
  const double rate = flops / t.product / 1e9;
  std::printf(
      "%s: N %ld W %ld  iteration %.3f s (Jacobian %.3f, J^T J + J^T e %.3f, Cholesky %.3f, "
      "trial SSE %.3f)\n",
      name, static_cast<long>(n), static_cast<long>(w), t.evaluate + t.product + t.solve + t.trial,
      t.evaluate, t.product, t.solve, t.trial);
  std::printf(
      "%s: J^T J %.2f GFLOP/s, Eigen GEMM %.2f GFLOP/s, GEMM / J^T J = %.2fx (target <= 2x) %s\n",
      name, rate, gemm, gemm / rate, gemm / rate <= 2.0 ? "PASS" : "FAIL");
}

// Seed-000 network with a teacher of the same shape (+ noise 0.1) as targets.
struct Seed000Problem {
  Mlp mlp;
  Eigen::MatrixXd x, y;
  Eigen::VectorXd w0;
};
Seed000Problem seed000_problem() {
  constexpr Eigen::Index kSamples = 13860;  // 70 % of 19,800 (seed 000)
  MlpOptions mo;
  mo.inputs = 73;
  mo.hidden = {28, 20};
  mo.outputs = 1;
  mo.hidden_activation = Activation::relu;
  mo.weights = {Initializer::Kind::normal, 0.0, 0.1};
  Seed000Problem p{Mlp(mo), Eigen::MatrixXd(73, kSamples), Eigen::MatrixXd(), Eigen::VectorXd()};
  Rng rng(11);
  for (Eigen::Index i = 0; i < p.x.size(); ++i) p.x.data()[i] = rng.normal();
  Eigen::VectorXd teacher;
  MlpOptions to = mo;
  to.weights = {Initializer::Kind::he};
  Mlp(to).initialise(teacher, rng);
  p.y = p.mlp.predict(teacher, p.x);
  for (Eigen::Index i = 0; i < p.y.size(); ++i) p.y.data()[i] += 0.1 * rng.normal();
  p.mlp.initialise(p.w0, rng);
  return p;
}

// Seed 002's NARX (12 tanh units, 4 input and 4 feedback delays, 121
// parameters) on an 86,000-step series the size of its training half:
// v(t) = 0.95 v(t-1) + 0.2 n(t), e(t) = 0.8 e(t-1) + 0.3 v(t) - 0.1 v(t-1).
// One trainbr stage's iteration in open loop (static network) and closed loop
// (RTRL Jacobian: "Jacobian" is the sequential simulation with the dynamic
// derivatives, "trial SSE" one simulation without them). The tanh output
// layer keeps the closed loop finite for any weights.
struct NarxProblem {
  Narx narx;
  Eigen::VectorXd v, e, w;
};
NarxProblem narx_problem() {
  constexpr Eigen::Index kSteps = 86000;
  NarxOptions o;
  o.hidden = 12;
  o.input_delays = 4;
  o.feedback_delays = 4;
  NarxProblem p{Narx(o), Eigen::VectorXd::Zero(kSteps), Eigen::VectorXd::Zero(kSteps),
                Eigen::VectorXd()};
  Rng rng(3);
  for (Eigen::Index t = 1; t < kSteps; ++t) {
    p.v[t] = 0.95 * p.v[t - 1] + 0.2 * rng.normal();
    p.e[t] = 0.8 * p.e[t - 1] + 0.3 * p.v[t] - 0.1 * p.v[t - 1];
  }
  p.narx.initialise(p.w, rng);
  return p;
}

void narx_iterations(int repeats, double gemm) {
  const NarxProblem p = narx_problem();
  const Eigen::Index n = p.v.size() - p.narx.first_step();
  NarxOpenLoopObjective open(p.narx, p.v, p.e);
  report("narx open loop 12/4", n, p.w.size(), time_iteration(open, p.w, repeats), gemm);
  NarxClosedLoopObjective closed(p.narx, p.v, p.e);
  report("narx closed loop 12/4", n, p.w.size(), time_iteration(closed, p.w, repeats), gemm);
}

// Eigen's GEMM C = A B (n x n, 2 n^3 flops) at one level, through that
// level's kernel table (the GEMM compiled with the level's flags).
double level_gemm_gflops(const kernels::Table& t, int repeats) {
  const Eigen::Index n = 1024;
  Rng rng(1);
  Eigen::MatrixXd a(n, n), b(n, n), c(n, n);
  for (Eigen::Index i = 0; i < a.size(); ++i) a.data()[i] = rng.normal();
  for (Eigen::Index i = 0; i < b.size(); ++i) b.data()[i] = rng.normal();
  std::vector<double> rates;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    kernels::multiply(t, a, false, b, false, c);
    rates.push_back(2.0 * n * n * n / seconds_since(t0) / 1e9);
  }
  if (!c.allFinite()) std::abort();
  return median(rates);
}

// J^T J of the NARX 12/4 closed-loop Jacobian (86,000 x 121, evaluated once
// in the row blocks NormalEquationBuilder uses) at every level this CPU
// runs, rounds alternating between the levels so that the machine's load
// falls on all of them alike; each level's GEMM rate in the same rounds.
int gram(int repeats) {
  const NarxProblem p = narx_problem();
  NarxClosedLoopObjective closed(p.narx, p.v, p.e);
  const Eigen::Index n = closed.num_residuals(), w = closed.num_parameters();
  const Eigen::Index block = NormalEquationBuilder(closed).block_rows();
  std::vector<Eigen::MatrixXd> blocks;
  Eigen::VectorXd e(block);
  for (Eigen::Index first = 0; first < n; first += block) {
    const Eigen::Index count = std::min(block, n - first);
    blocks.emplace_back(count, w);
    closed.evaluate(p.w, first, count, e.head(count), &blocks.back());
  }
  std::vector<IsaLevel> levels;
  for (const IsaLevel l : compiled_isa_levels()) {
    if (cpu_supports(l)) levels.push_back(l);
  }
  const double flops = static_cast<double>(n) * static_cast<double>(w) * (w + 1.0);
  std::vector<std::vector<double>> gram_rates(levels.size()), gemm_rates(levels.size());
  Eigen::MatrixXd jtj(w, w);
  for (int r = 0; r < repeats; ++r) {
    for (std::size_t i = 0; i < levels.size(); ++i) {
      const kernels::Table& t = kernels::table_for(levels[i]);
      gemm_rates[i].push_back(level_gemm_gflops(t, 1));
      jtj.setZero();
      const auto t0 = Clock::now();
      for (const Eigen::MatrixXd& j : blocks) {
        t.dsyrk(true, w, j.rows(), j.data(), j.outerStride(), jtj.data(), jtj.outerStride());
      }
      gram_rates[i].push_back(flops / seconds_since(t0) / 1e9);
      if (!jtj.allFinite()) std::abort();
    }
  }
  std::printf(
      "narx closed loop 12/4 J^T J (N %ld W %ld, blocks of %ld rows), 1 thread, median of "
      "%d rounds:\n",
      static_cast<long>(n), static_cast<long>(w), static_cast<long>(block), repeats);
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const double g = median(gram_rates[i]), m = median(gemm_rates[i]);
    const bool v4 = levels[i] == IsaLevel::v4;
    std::printf(
        "  %-8s J^T J %6.2f GFLOP/s, Eigen GEMM 1024^2 %6.2f GFLOP/s, GEMM / J^T J = %.2fx%s\n",
        to_string(levels[i]), g, m, m / g,
        v4 ? (m / g <= 1.3 ? " (target <= 1.3x) PASS" : " (target <= 1.3x) FAIL") : "");
  }
  return 0;
}

void write_binary(const std::filesystem::path& file, const double* data, Eigen::Index count) {
  std::ofstream out(file, std::ios::binary);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(count * 8));
  if (!out) {
    std::fprintf(stderr, "cannot write %s\n", file.c_str());
    std::exit(1);
  }
}

int iteration(int repeats) {
  const double gemm = gemm_gflops(repeats);
  std::printf("Eigen GEMM 1024 x 1024: %.2f GFLOP/s (1 thread, median of %d)\n", gemm, repeats);
  {
    constexpr Eigen::Index kRows = 85000, kCols = 121;
    Rng rng(2);
    Eigen::MatrixXd j(kRows, kCols);
    Eigen::VectorXd t(kRows), w = Eigen::VectorXd::Zero(kCols);
    for (Eigen::Index i = 0; i < j.size(); ++i) j.data()[i] = rng.normal();
    for (Eigen::Index i = 0; i < t.size(); ++i) t[i] = rng.normal();
    DenseResiduals dense(std::move(j), std::move(t));
    report("85000x121", kRows, kCols, time_iteration(dense, w, repeats), gemm);
  }
  const Seed000Problem p = seed000_problem();
  MlpResidualObjective objective(p.mlp, p.x, p.y);
  report("seed-000 73-28-20-1", p.y.cols(), p.w0.size(),
         time_iteration(objective, p.w0, std::max(1, repeats / 2)), gemm);
  narx_iterations(repeats, gemm);
  return 0;
}

int prepare(const std::filesystem::path& dir) {
  const Seed000Problem p = seed000_problem();
  std::filesystem::create_directories(dir);
  // x sample-major (N x 73, C order), the same bytes as Eigen's 73 x N.
  write_binary(dir / "x.bin", p.x.data(), p.x.size());
  write_binary(dir / "y.bin", p.y.data(), p.y.size());
  write_binary(dir / "w0.bin", p.w0.data(), p.w0.size());
  std::printf("samples %ld inputs 73 hidden 28 20 parameters %ld\n", static_cast<long>(p.x.cols()),
              static_cast<long>(p.w0.size()));
  return 0;
}

int race(double target_sse) {
  const Seed000Problem p = seed000_problem();
  MlpResidualObjective objective(p.mlp, p.x, p.y);
  Eigen::VectorXd w = p.w0;
  LmOptions o;  // trainlm defaults
  o.epochs = 100;
  LmHooks hooks;
  hooks.on_epoch = [&](const EpochRecord&, const LmEpochRecord& lm, const Eigen::VectorXd&) {
    return lm.sse > target_sse;
  };
  const auto t0 = Clock::now();
  const Summary s = train_lm(objective, w, o, hooks);
  const double sec = seconds_since(t0);
  const double sse = s.lm_history.empty() ? std::nan("") : s.lm_history.back().sse;
  std::printf("seconds %.3f sse %.9g epochs %zu reached %d\n", sec, sse, s.lm_history.size(),
              sse <= target_sse ? 1 : 0);
  return 0;
}

// trainbr for EPOCHS epochs on a 73-32-16-1 ReLU network with 936 samples
// (teacher of the same shape + noise 0.1), in `form` with `decomposition`.
struct FormRun {
  double seconds_per_epoch;
  Eigen::VectorXd w;
  double gamma;
};
FormRun trainbr_run(LmForm form, LmDecomposition decomposition, std::size_t epochs) {
  constexpr Eigen::Index kSamples = 936;
  MlpOptions mo;
  mo.inputs = 73;
  mo.hidden = {32, 16};
  mo.outputs = 1;
  mo.hidden_activation = Activation::relu;
  mo.weights = {Initializer::Kind::normal, 0.0, 0.1};
  const Mlp mlp(mo);
  Rng rng(12);
  Eigen::MatrixXd x(73, kSamples);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = rng.normal();
  Eigen::VectorXd teacher, w;
  MlpOptions to = mo;
  to.weights = {Initializer::Kind::he};
  Mlp(to).initialise(teacher, rng);
  Eigen::MatrixXd y = mlp.predict(teacher, x);
  for (Eigen::Index i = 0; i < y.size(); ++i) y.data()[i] += 0.1 * rng.normal();
  mlp.initialise(w, rng);
  MlpResidualObjective objective(mlp, x, y);
  TrainbrOptions o;
  o.epochs = epochs;
  o.min_gradient = 0;
  o.form = form;
  o.decomposition = decomposition;
  const auto t0 = Clock::now();
  const Summary s = train_trainbr(objective, w, o);
  const double sec = seconds_since(t0);
  if (s.lm_history.size() != epochs) {
    std::fprintf(stderr, "trainbr stopped early: %s\n", s.message.c_str());
    std::exit(1);
  }
  return {sec / static_cast<double>(epochs), w, s.lm_history.back().gamma};
}

int forms(std::size_t epochs) {
  const FormRun before = trainbr_run(LmForm::primal, LmDecomposition::cholesky, epochs);
  const FormRun now = trainbr_run(LmForm::automatic, LmDecomposition::automatic, epochs);
  const double ratio = before.seconds_per_epoch / now.seconds_per_epoch;
  const double diff = (now.w - before.w).norm() / before.w.norm();
  const double dgamma = std::abs(now.gamma - before.gamma) / before.gamma;
  std::printf("trainbr 73-32-16-1 (2913 weights), 936 samples, %zu epochs, 1 thread:\n", epochs);
  std::printf("  primal J^T J, Cholesky per mu:  %.3f s/epoch\n", before.seconds_per_epoch);
  std::printf("  automatic (dual J J^T, spectral): %.3f s/epoch\n", now.seconds_per_epoch);
  std::printf(
      "  speed-up %.1fx (target >= 5x), weights differ by %.1e relative, gamma by %.1e "
      "(target <= 1e-9) %s\n",
      ratio, diff, dgamma, ratio >= 5 && diff <= 1e-9 && dgamma <= 1e-9 ? "PASS" : "FAIL");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "iteration";
  if (mode == "iteration") return iteration(argc > 2 ? std::atoi(argv[2]) : 3);
  if (mode == "prepare" && argc > 2) return prepare(argv[2]);
  if (mode == "race" && argc > 3) return race(std::atof(argv[3]));
  if (mode == "gram") return gram(argc > 2 ? std::atoi(argv[2]) : 3);
  if (mode == "forms") return forms(argc > 2 ? std::strtoul(argv[2], nullptr, 10) : 5);
  std::fprintf(stderr,
               "usage: %s iteration [REPEATS] | gram [REPEATS] | prepare DIR | race DIR TARGET_SSE "
               "| forms [EPOCHS]\n",
               argv[0]);
  return 2;
}
