// Training throughput of the seed-000 network shape, single thread:
// 73 inputs -> 28 ReLU -> dropout (keep 0.5) -> 20 ReLU -> 1 linear,
// SGDM eta 1e-5, beta 0.8, on 13,860 samples (70 % of 19,800).
// Prints one line per batch size and precision (trainer.precision, sgdm.hpp):
// "batch <b> samples_per_s <x> precision <float64|float32>" (median of
// repeats). scripts/bench_train runs this beside the PyTorch equivalent.
//
//   cnclab_bench_train [REPEATS [BATCH [PRECISION]]]   (default 5, all batch
//   sizes 1 / 32 / 256, both precisions; BATCH or PRECISION "all" = every one)
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "cnclab/core/rng.hpp"
#include "cnclab/nn/mlp.hpp"
#include "cnclab/train/objective.hpp"
#include "cnclab/train/sgdm.hpp"

int main(int argc, char** argv) {
  using namespace cnclab;
  constexpr Eigen::Index kSamples = 13860;
  const int repeats = argc > 1 ? std::atoi(argv[1]) : 5;
  const std::string only_batch = argc > 2 ? argv[2] : "all";
  const std::string only_precision = argc > 3 ? argv[3] : "all";
  if (repeats < 1) {
    std::fprintf(stderr, "usage: cnclab_bench_train [REPEATS >= 1 [BATCH [PRECISION]]]\n");
    return 2;
  }
  Rng data_rng(1);
  Eigen::MatrixXd x(73, kSamples), y(1, kSamples);
  for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = data_rng.normal();
  for (Eigen::Index i = 0; i < y.size(); ++i) y.data()[i] = data_rng.normal();

  MlpOptions mo;
  mo.inputs = 73;
  mo.hidden = {28, 20};
  mo.outputs = 1;
  mo.dropout_keep_probability = 0.5;
  // Small weights keep the benchmark numerically tame (the paper's N(0, 1)
  // does not change the amount of work).
  mo.weights = {Initializer::Kind::normal, 0.0, 0.1};
  const Mlp mlp(mo);

  for (const Precision precision : {Precision::float64, Precision::float32}) {
    const char* precision_name = precision == Precision::float32 ? "float32" : "float64";
    if (only_precision != "all" && only_precision != precision_name) continue;
    for (std::size_t batch : {1, 32, 256}) {
      if (only_batch != "all" && only_batch != std::to_string(batch)) continue;
      // Enough epochs for ~0.5 s per measurement at each batch size.
      const std::size_t epochs = batch == 1 ? 2 : 10;
      std::vector<double> rates;
      for (int r = 0; r < repeats; ++r) {
        Rng init(2), dropout(3), shuffle(4);
        Eigen::VectorXd p;
        mlp.initialise(p, init);
        MlpRegressionObjective objective(mlp, x, y, dropout);
        SgdmOptions o;
        o.learning_rate = 1e-5;
        o.momentum = 0.8;
        o.batch_size = batch;
        o.epochs = epochs;
        o.precision = precision;
        const auto t0 = std::chrono::steady_clock::now();
        const Summary s = train_sgdm(objective, p, o, shuffle);
        const double sec =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        if (s.termination != Termination::max_epochs) {
          std::fprintf(stderr, "benchmark training stopped: %s\n", s.message.c_str());
          return 1;
        }
        rates.push_back(static_cast<double>(kSamples * epochs) / sec);
      }
      std::sort(rates.begin(), rates.end());
      std::printf("batch %zu samples_per_s %.0f precision %s\n", batch, rates[rates.size() / 2],
                  precision_name);
    }
  }
  return 0;
}
