#pragma once
// Random train / validation / test splits of sample indices.
#include <cstddef>
#include <vector>

#include "cnclab/core/rng.hpp"

namespace cnclab {

struct SplitOptions {
  double train_fraction = 0.7;       // share of all samples used for training (seed 000: 70 %)
  double validation_fraction = 0.0;  // share held out of training for early stopping
  // test = the rest. validate(): train in (0, 1], validation in [0, 1), sum <= 1.
  void validate() const;
};

struct Split {
  std::vector<std::size_t> train, validation, test;  // each sorted ascending
};

// A uniformly random partition: one Fisher-Yates shuffle of 0..n-1 with
// `rng` (n - 1 draws of rng.below), cut into
//   n_train      = round(train_fraction * n),
//   n_validation = min(round(validation_fraction * n), n - n_train),
//   n_test       = n - n_train - n_validation,
// with round = std::llround (halves away from zero). Deterministic given the
// rng state; each part is sorted ascending.
Split make_random_split(std::size_t n, const SplitOptions& options, Rng& rng);

}  // namespace cnclab
