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

// A uniformly random partition (Fisher-Yates with `rng`):
// n_train = round(train_fraction * n), n_validation = round(validation_fraction * n)
// (capped so the parts never exceed n), test = the rest.
Split make_random_split(std::size_t n, const SplitOptions& options, Rng& rng);

}  // namespace cnclab
