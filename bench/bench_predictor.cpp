// NARX benchmark, seed 002's network (12 tanh neurons, 4 input and
// 4 feedback delays), single thread:
//   (1) one trainbr iteration in the parallel (closed-loop) configuration --
//       dynamic Jacobian by RTRL, J^T J, one LM step and its trial
//       simulation, the alpha/beta re-estimation -- against one
//       series-parallel (open-loop) iteration on the same training half;
//       target ratio <= 3;
//   (2) the real-time contour predictor per 1 ms tick (both axes + the Taylor
//       estimate) against the 5 us target and the 1 ms tick budget;
//   (3) the same predictor as `cnclab export --format c` writes it, compiled
//       with this build's C compiler and flags, on the same ticks: its time
//       against (2)'s (target ratio <= 1.5), its agreement with (2), and the
//       heap allocations of both tick loops (counted: exported_predictor.hpp)
//       and the exported code's imports (nm: no allocator among them).
// Data: the motion pipeline, as scripts/bench_motion: an epitrochoid path
// (analytic_paths.hpp, 33 turns: ~87 s) planned with Ipopt, interpolated at
// 1 ms and run on the simulated biaxial router; the x/y reference velocities
// and following errors normalised to [-1, 1] (mapminmax) are the training
// half (>= 85,000 steps, seed 002: "over 170000 samples ... divided in
// half"). --synthetic replaces the pipeline by a sum of sines through a
// first-order lag of the same length (no Ipopt; the timings do not depend on
// the values).
//
// Times are this thread's CPU time (CLOCK_THREAD_CPUTIME_ID): the machine
// may be shared, and wall time then measures the neighbours.
//
// Usage: cnclab_bench_predictor [--synthetic] [TURNS] [REPEATS]
#include <Eigen/Cholesky>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "cnclab/core/rng.hpp"
#include "cnclab/motion/analytic_paths.hpp"
#include "cnclab/motion/contour_error.hpp"
#include "cnclab/motion/feedrate_planner.hpp"
#include "cnclab/motion/interpolator.hpp"
#include "cnclab/motion/machine.hpp"
#include "cnclab/studies/contour_error/contour_deployment.hpp"
#include "cnclab/studies/contour_error/contour_predictor.hpp"
#include "cnclab/train/lm.hpp"
#include "cnclab/train/narx_training.hpp"
#include "cnclab/train/normal_equations.hpp"
#include "cnclab/train/trainbr.hpp"
#include "exported_predictor.hpp"

namespace {
using namespace cnclab;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One axis's series in physical units.
struct AxisSeries {
  Eigen::VectorXd velocity;  // reference velocity [mm/s]
  Eigen::VectorXd error;     // following error [mm]
};

struct BenchData {
  std::string source;
  AxisSeries axes[2];
  std::vector<PathPoint> reference;  // C(u), C'(u), C''(u) per tick (for the predictor)
};

BenchData motion_pipeline(double turns) {
  BenchData d;
  const EpitrochoidPath path(Vec2(0, 0), 100.0, 8.0, 7.0, turns);
  const auto t0 = Clock::now();
  const FeedrateProfile profile = plan_feedrate(path, FeedratePlannerOptions{});
  const ReferenceTrajectory reference = interpolate(path, profile, 1e-3);
  const MachineResponse response = simulate_machine(MachineOptions{}, reference, 1);
  char text[200];
  std::snprintf(text, sizeof text,
                "motion pipeline: epitrochoid, %.0f turns, planned %.1f s, simulated "
                "biaxial_router (%.1f s to prepare)",
                turns, profile.total_time(), seconds_since(t0));
  d.source = text;
  for (int a = 0; a < 2; ++a) {
    d.axes[a].velocity = reference.velocity.col(a);
    d.axes[a].error = response.following_error.col(a);
  }
  for (const double u : reference.u) d.reference.push_back(path.evaluate(u));
  return d;
}

// Sum of sines within +-300 mm/s through e' = (k v - e) / tau (a lagging
// following error), on a circle's geometry.
BenchData synthetic(Eigen::Index n) {
  BenchData d;
  d.source = "synthetic: sum of sines, first-order lag, " + std::to_string(n) + " steps";
  const CirclePath circle(Vec2(200, 200), 150.0, 0.0, 2 * 3.141592653589793 * 50);
  for (int a = 0; a < 2; ++a) {
    d.axes[a].velocity.resize(n);
    d.axes[a].error.resize(n);
    double e = 0;
    for (Eigen::Index t = 0; t < n; ++t) {
      const double s = static_cast<double>(t) * 1e-3;
      const double v =
          180 * std::sin(0.7 * s + a) + 90 * std::sin(5.3 * s + 2 * a) + 30 * std::sin(31.0 * s);
      e += 1e-3 * (2.5e-4 * v - e) / 0.05;
      d.axes[a].velocity[t] = v;
      d.axes[a].error[t] = e;
    }
  }
  for (Eigen::Index t = 0; t < n; ++t) {
    d.reference.push_back(circle.evaluate(static_cast<double>(t) / static_cast<double>(n)));
  }
  return d;
}

Eigen::VectorXd normalised(const Eigen::VectorXd& x, const MinMaxNormaliser& n) {
  return n.transform(x.transpose()).transpose();
}
MinMaxNormaliser fitted(const Eigen::VectorXd& x) {
  MinMaxNormaliser n;
  n.fit(x.transpose());
  return n;
}

// One trainbr iteration as levenberg_marquardt does it with one accepted
// trial: normal equations (Jacobian + J^T J + J^T e), the damped Cholesky
// solve, the trial's sum of squares, the effective-parameter count.
struct IterationTiming {
  double total = 0, jacobian = 0, products = 0, trial = 0;  // CPU seconds
  double wall = 0;
};
IterationTiming iteration(ResidualObjective& objective, const Eigen::VectorXd& params,
                          int repeats) {
  std::vector<double> total, jac, prod, trial, wall;
  const Eigen::Index w = objective.num_parameters();
  for (int r = 0; r < repeats; ++r) {
    NormalEquationBuilder builder(objective);
    NormalEquations ne;
    const auto wall0 = Clock::now();
    const double t0 = cpu_seconds();
    builder.build(params, ne);
    const double t_build = cpu_seconds() - t0;
    const double beta = 1.0, alpha = 0.01, mu = 1e-3;
    Eigen::MatrixXd damped(w, w);
    damped.triangularView<Eigen::Lower>() = beta * ne.jtj;
    damped.diagonal().array() += mu + alpha;
    const Eigen::LLT<Eigen::MatrixXd, Eigen::Lower> llt(damped);
    const Eigen::VectorXd step = llt.solve(-(beta * ne.jte + alpha * params));
    const double t1 = cpu_seconds();
    const double sse = builder.sum_of_squares(params + 1e-3 * step);
    const double t_trial = cpu_seconds() - t1;
    const double gamma = effective_parameters(ne.jtj, alpha, beta);
    total.push_back(cpu_seconds() - t0);
    wall.push_back(seconds_since(wall0));
    // The builder's split is in wall time; scale it to the build's CPU time.
    const NormalEquationTiming& bt = builder.timing();
    const double share = bt.evaluate_seconds / (bt.evaluate_seconds + bt.product_seconds);
    jac.push_back(share * t_build);
    prod.push_back((1 - share) * t_build);
    trial.push_back(t_trial);
    if (!std::isfinite(sse) || !std::isfinite(gamma)) std::printf("  (non-finite SSE or gamma)\n");
  }
  return {median(total), median(jac), median(prod), median(trial), median(wall)};
}

}  // namespace

int main(int argc, char** argv) {
  bool use_synthetic = false;
  std::vector<double> numbers;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--synthetic") == 0) {
      use_synthetic = true;
    } else {
      numbers.push_back(std::atof(argv[i]));
    }
  }
  const double turns = numbers.size() > 0 ? numbers[0] : 33.0;
  const int repeats = numbers.size() > 1 ? static_cast<int>(numbers[1]) : 3;
  constexpr Eigen::Index kMinSteps = 85000;

  const BenchData data = use_synthetic ? synthetic(kMinSteps + 2000) : motion_pipeline(turns);
  const Eigen::Index n = data.axes[0].velocity.size();
  std::printf("data: %s\n  %ld steps per axis (training half of a >= %ld-sample run: %s)\n",
              data.source.c_str(), static_cast<long>(n), 2 * kMinSteps,
              n >= kMinSteps ? "yes" : "NO, too short");

  const NarxOptions options;  // seed 002: 12 tanh neurons, 4/4 delays
  const Narx narx(options);
  NarxAxisModel models[2];
  std::printf("network: %zu hidden, %zu input / %zu feedback delays, %zu weights\n", options.hidden,
              options.input_delays, options.feedback_delays, narx.num_parameters());

  // Weights: a short open-loop trainbr run per axis (realistic, stable).
  TrainbrOptions warm_up = seed002_trainbr();
  warm_up.epochs = 8;
  Eigen::VectorXd vn[2], en[2];
  for (int a = 0; a < 2; ++a) {
    models[a].options = options;
    models[a].input = fitted(data.axes[a].velocity);
    models[a].output = fitted(data.axes[a].error);
    vn[a] = normalised(data.axes[a].velocity, models[a].input);
    en[a] = normalised(data.axes[a].error, models[a].output);
    Rng rng(100 + a);
    models[a].params.resize(static_cast<Eigen::Index>(narx.num_parameters()));
    narx.initialise(models[a].params, rng);
    NarxOpenLoopObjective open(narx, vn[a], en[a]);
    train_trainbr(open, models[a].params, warm_up);
  }

  // (1) trainbr iteration, x axis.
  NarxOpenLoopObjective open(narx, vn[0], en[0]);
  NarxClosedLoopObjective closed(narx, vn[0], en[0]);
  const IterationTiming t_open = iteration(open, models[0].params, repeats);
  const IterationTiming t_closed = iteration(closed, models[0].params, repeats);
  std::printf("\ntrainbr iteration on %ld steps (median of %d; Jacobian + J^T J + step + trial)\n",
              static_cast<long>(open.num_residuals()), repeats);
  std::printf("  CPU seconds                  %9s %9s %9s %9s %9s\n", "total", "Jacobian", "J^T J",
              "trial", "(wall)");
  std::printf("  %-28s %9.3f %9.3f %9.3f %9.3f %9.3f\n", "open loop (series-parallel)",
              t_open.total, t_open.jacobian, t_open.products, t_open.trial, t_open.wall);
  std::printf("  %-28s %9.3f %9.3f %9.3f %9.3f %9.3f\n", "closed loop (parallel, RTRL)",
              t_closed.total, t_closed.jacobian, t_closed.products, t_closed.trial, t_closed.wall);
  std::printf("  closed / open ratio          %9.2f   (target <= 3)\n",
              t_closed.total / t_open.total);

  // (2) predictor per tick, over the whole series, repeated.
  ContourPredictor predictor(models[0], models[1]);
  std::vector<Vec2> velocity(static_cast<std::size_t>(n));
  for (Eigen::Index t = 0; t < n; ++t) {
    velocity[static_cast<std::size_t>(t)] =
        Vec2(data.axes[0].velocity[t], data.axes[1].velocity[t]);
  }
  std::vector<double> per_tick, per_axis_step, per_taylor;
  double checksum = 0;
  long failed = 0, internal_allocations = 0;
  for (int r = 0; r < std::max(repeats, 3); ++r) {
    predictor.reset();
    ContourPrediction out;
    const long allocations_before = bench::allocation_count();
    double t0 = cpu_seconds();
    for (Eigen::Index t = 0; t < n; ++t) {
      const auto k = static_cast<std::size_t>(t);
      if (predictor.step(velocity[k], data.reference[k], out) != PredictorStatus::ok) ++failed;
      checksum += out.contour_error;
    }
    const double seconds = cpu_seconds() - t0;
    internal_allocations =
        std::max(internal_allocations, bench::allocation_count() - allocations_before);
    per_tick.push_back(seconds / static_cast<double>(n));
    // Breakdown: one axis network alone, the Taylor estimate alone.
    NarxPredictor& x = predictor.axis(0);
    x.reset();
    double e = 0;
    t0 = cpu_seconds();
    for (Eigen::Index t = 0; t < n; ++t) {
      x.step(data.axes[0].velocity[t], e);
      checksum += e;
    }
    per_axis_step.push_back((cpu_seconds() - t0) / static_cast<double>(n));
    t0 = cpu_seconds();
    for (Eigen::Index t = 0; t < n; ++t) {
      const auto k = static_cast<std::size_t>(t);
      checksum +=
          taylor_contour_error(data.reference[k], data.reference[k].position - Vec2(1e-2, -2e-2));
    }
    per_taylor.push_back((cpu_seconds() - t0) / static_cast<double>(n));
  }
  const double tick_us = median(per_tick) * 1e6;
  std::printf("\ncontour predictor per 1 ms tick (CPU time, median of %zu passes over %ld ticks)\n",
              per_tick.size(), static_cast<long>(n));
  std::printf(
      "  both axes + Taylor estimate  %9.3f us   (target 5 us: %.1f x under; 1 ms tick: "
      "%.2f %% of it)\n",
      tick_us, 5.0 / tick_us, tick_us / 1000.0 * 100.0);
  std::printf("  one axis network             %9.3f us\n", median(per_axis_step) * 1e6);
  std::printf("  Taylor estimate (Eqs. 3-6)   %9.3f us\n", median(per_taylor) * 1e6);
  if (failed > 0) std::printf("  %ld ticks returned a non-ok status\n", failed);
  std::printf("  (checksum %.6g)\n", checksum);

  // (3) The exported C predictor on the same ticks.
  register_contour_deployment();
  const bench::ExportedTiming c =
      bench::time_exported_predictor(models, velocity, data.reference, repeats);
  const double c_us = c.tick_seconds * 1e6;
  std::printf("\nexported C predictor (cnclab export --format c; %s)\n", c.compile.c_str());
  std::printf(
      "  both axes + Taylor estimate  %9.3f us   internal %.3f us: ratio %.2f "
      "(target <= 1.5)\n",
      c_us, tick_us, c_us / tick_us);
  std::printf("  agreement with (2)           max |e| diff %.3g um, max contour diff %.3g um\n",
              c.max_error_diff, c.max_contour_diff);
  if (bench::allocation_count() < 0) {
    std::printf("  heap allocations             not counted (a sanitizer owns malloc)\n");
  } else {
    std::printf("  heap allocations per pass    exported %ld, internal %ld (target 0)\n",
                c.allocations, internal_allocations);
  }
  std::printf("  imports (nm -D -u)          ");
  bool allocator = false;
  for (const auto& symbol : c.imports) {
    std::printf(" %s", symbol.c_str());
    allocator = allocator || symbol.find("alloc") != std::string::npos || symbol == "free";
  }
  std::printf("\n  allocator among the imports  %s\n", allocator ? "YES" : "none");
  return 0;
}
